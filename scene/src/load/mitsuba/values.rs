//! The text of attribute values: numbers, triples, RGB, spectrum text and `.spd` files,
//! and the 4x4 matrices of `<transform>` operations. Every function returns the reason in
//! words when the text does not fit; the parser adds where.
//!
//! Mitsuba reads lists split at commas and whitespace ("1, 2, 3", "1 2 3"), and numbers
//! with surrounding whitespace ("1", "1.0", " 1e-3 ").

use super::tree::SpectrumValue;

/// A row-major 4x4 matrix.
pub type Matrix = [[f64; 4]; 4];

/// The pieces of a list: split at commas and whitespace, empty pieces dropped.
pub fn tokens(text: &str) -> Vec<&str> {
    text.split(|c: char| c == ',' || c.is_whitespace())
        .filter(|t| !t.is_empty())
        .collect()
}

/// A floating-point number.
pub fn float(text: &str) -> Result<f64, String> {
    text.trim()
        .parse::<f64>()
        .map_err(|_| format!("could not parse floating point value \"{text}\""))
}

/// An integer.
pub fn integer(text: &str) -> Result<i64, String> {
    text.trim()
        .parse::<i64>()
        .map_err(|_| format!("could not parse integer value \"{text}\""))
}

/// "true" or "false", in any case.
pub fn boolean(text: &str) -> Result<bool, String> {
    match text.trim().to_ascii_lowercase().as_str() {
        "true" => Ok(true),
        "false" => Ok(false),
        _ => Err(format!(
            "could not parse boolean value \"{text}\" (must be \"true\" or \"false\")"
        )),
    }
}

/// Exactly `n` numbers.
pub fn floats<const N: usize>(text: &str) -> Result<[f64; N], String> {
    let list = tokens(text);
    if list.len() != N {
        return Err(format!(
            "expected {N} numbers, got {} in \"{text}\"",
            list.len()
        ));
    }
    let mut out = [0.0; N];
    for (o, t) in out.iter_mut().zip(list) {
        *o = float(t)?;
    }
    Ok(out)
}

/// One number repeated three times, or three numbers (`value` of `<point>`, `<rgb>`...).
pub fn one_or_three(text: &str) -> Result<[f64; 3], String> {
    let list = tokens(text);
    match list.as_slice() {
        [a] => {
            let v = float(a)?;
            Ok([v, v, v])
        }
        [a, b, c] => Ok([float(a)?, float(b)?, float(c)?]),
        _ => Err(format!(
            "expected 1 or 3 numbers, got {} in \"{text}\"",
            list.len()
        )),
    }
}

/// A spectrum's `value`: one number (constant) or `wavelength:value` pairs.
pub fn spectrum_text(text: &str) -> Result<SpectrumValue, String> {
    let list = tokens(text);
    if let [single] = list.as_slice()
        && !single.contains(':')
    {
        return float(single).map(SpectrumValue::Constant);
    }
    if list.is_empty() {
        return Err("empty spectrum value".into());
    }
    let mut samples = Vec::with_capacity(list.len());
    for token in list {
        let Some((lambda, value)) = token.split_once(':') else {
            return Err(format!(
                "invalid spectrum \"{text}\" (expected wavelength:value pairs)"
            ));
        };
        samples.push((float(lambda)?, float(value)?));
    }
    increasing(samples)
}

/// The text of a `.spd` file: one "wavelength value" pair a line, `#` starts a comment.
pub fn spd_file(text: &str) -> Result<SpectrumValue, String> {
    let mut samples = Vec::new();
    for (n, line) in text.lines().enumerate() {
        let line = line.split('#').next().unwrap_or("");
        let list = tokens(line);
        match list.as_slice() {
            [] => {}
            [lambda, value] => samples.push((float(lambda)?, float(value)?)),
            _ => {
                return Err(format!(
                    "line {} of the spectrum file: expected \"wavelength value\"",
                    n + 1
                ));
            }
        }
    }
    if samples.is_empty() {
        return Err("the spectrum file has no samples".into());
    }
    increasing(samples)
}

fn increasing(samples: Vec<(f64, f64)>) -> Result<SpectrumValue, String> {
    let decreasing = |w: &[(f64, f64)]| match w {
        [(a, _), (b, _)] => b.partial_cmp(a).is_none_or(std::cmp::Ordering::is_lt),
        _ => false,
    };
    if samples.windows(2).any(decreasing) {
        return Err("wavelengths must be given in increasing order".into());
    }
    Ok(SpectrumValue::Samples(samples))
}

/// The identity matrix.
pub const IDENTITY: Matrix = [
    [1.0, 0.0, 0.0, 0.0],
    [0.0, 1.0, 0.0, 0.0],
    [0.0, 0.0, 1.0, 0.0],
    [0.0, 0.0, 0.0, 1.0],
];

/// `a * b`.
pub fn multiply(a: &Matrix, b: &Matrix) -> Matrix {
    let mut out = [[0.0; 4]; 4];
    for (i, row) in out.iter_mut().enumerate() {
        for (j, cell) in row.iter_mut().enumerate() {
            *cell = (0..4).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    out
}

/// A translation by `v`.
pub fn translate(v: [f64; 3]) -> Matrix {
    let mut m = IDENTITY;
    for (row, t) in m.iter_mut().zip(v) {
        row[3] = t;
    }
    m
}

/// A scale by `v` along the axes.
pub fn scale(v: [f64; 3]) -> Matrix {
    let mut m = IDENTITY;
    for (i, s) in v.into_iter().enumerate() {
        m[i][i] = s;
    }
    m
}

/// A right-handed rotation by `degrees` about `axis` (normalised here).
pub fn rotate(axis: [f64; 3], degrees: f64) -> Result<Matrix, String> {
    let [x, y, z] = normalize(axis).ok_or("the rotation axis is zero")?;
    let (s, c) = degrees.to_radians().sin_cos();
    let t = 1.0 - c;
    Ok([
        [t * x * x + c, t * x * y - s * z, t * x * z + s * y, 0.0],
        [t * x * y + s * z, t * y * y + c, t * y * z - s * x, 0.0],
        [t * x * z - s * y, t * y * z + s * x, t * z * z + c, 0.0],
        [0.0, 0.0, 0.0, 1.0],
    ])
}

/// Mitsuba's look-at (`Transform4f::look_at`): a camera-to-world matrix whose columns are
/// `left = normalize(up x dir)`, `dir x left`, `dir = normalize(target - origin)` and the
/// origin, so the camera's local +z looks at the target and local +y is (close to) `up`.
/// A zero `up` picks one perpendicular to the direction, as Mitsuba does.
pub fn look_at(origin: [f64; 3], target: [f64; 3], up: [f64; 3]) -> Result<Matrix, String> {
    let dir = normalize(sub(target, origin)).ok_or("lookat: the origin is the target")?;
    let up = if dot(up, up) == 0.0 {
        any_perpendicular(dir)
    } else {
        up
    };
    let left = normalize(cross(up, dir)).ok_or("lookat: up is parallel to the view direction")?;
    let new_up = cross(dir, left);
    let mut m = IDENTITY;
    for i in 0..3 {
        m[i][0] = left[i];
        m[i][1] = new_up[i];
        m[i][2] = dir[i];
        m[i][3] = origin[i];
    }
    if m.iter().flatten().any(|v| !v.is_finite()) {
        return Err("invalid lookat transformation".into());
    }
    Ok(m)
}

/// A unit vector perpendicular to the unit vector `n` (Duff et al. 2017, "Building an
/// orthonormal basis, revisited": the first vector of the basis, as Mitsuba's
/// `coordinate_system`).
fn any_perpendicular(n: [f64; 3]) -> [f64; 3] {
    let sign = 1.0_f64.copysign(n[2]);
    let a = -1.0 / (sign + n[2]);
    let b = n[0] * n[1] * a;
    [1.0 + sign * n[0] * n[0] * a, sign * b, -sign * n[0]]
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn normalize(v: [f64; 3]) -> Option<[f64; 3]> {
    let length = dot(v, v).sqrt();
    (length > 0.0 && length.is_finite()).then(|| [v[0] / length, v[1] / length, v[2] / length])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: &Matrix, b: &Matrix) -> bool {
        a.iter()
            .flatten()
            .zip(b.iter().flatten())
            .all(|(x, y)| (x - y).abs() < 1e-12)
    }

    #[test]
    fn numbers_with_whitespace_and_exponents() {
        assert_eq!(float(" 1e-3 "), Ok(1e-3));
        assert_eq!(float("1"), Ok(1.0));
        assert!(float("abc").is_err());
        assert_eq!(integer(" 42 "), Ok(42));
        assert!(integer("4.2").is_err());
        assert_eq!(boolean("TRUE"), Ok(true));
        assert!(boolean("yes").is_err());
        assert_eq!(one_or_three("1, 2 3"), Ok([1.0, 2.0, 3.0]));
        assert_eq!(one_or_three("0.5"), Ok([0.5; 3]));
        assert!(one_or_three("1 2").is_err());
    }

    #[test]
    fn spectrum_forms() {
        assert_eq!(spectrum_text("0.5"), Ok(SpectrumValue::Constant(0.5)));
        assert_eq!(
            spectrum_text("400:0.1, 500:0.2"),
            Ok(SpectrumValue::Samples(vec![(400.0, 0.1), (500.0, 0.2)]))
        );
        assert!(spectrum_text("500:0.1, 400:0.2").is_err());
        assert!(spectrum_text("400:0.1, 500").is_err());
        assert_eq!(
            spd_file("# comment\n400 0.1\n\n 500  0.2 # tail\n"),
            Ok(SpectrumValue::Samples(vec![(400.0, 0.1), (500.0, 0.2)]))
        );
        assert!(spd_file("400 0.1 7\n").is_err());
    }

    #[test]
    fn rotation_about_y_takes_x_to_minus_z() {
        let r = rotate([0.0, 1.0, 0.0], 90.0).unwrap();
        // Column 0 is the image of +x.
        let x = [r[0][0], r[1][0], r[2][0]];
        assert!((x[0]).abs() < 1e-12 && (x[2] + 1.0).abs() < 1e-12, "{x:?}");
        assert!(rotate([0.0; 3], 10.0).is_err());
    }

    #[test]
    fn multiply_order() {
        let t = translate([1.0, 0.0, 0.0]);
        let s = scale([2.0; 3]);
        // Scale first, then translate: the origin goes to (1, 0, 0).
        let m = multiply(&t, &s);
        assert_eq!(m[0][3], 1.0);
        assert_eq!(m[0][0], 2.0);
        assert!(close(&multiply(&IDENTITY, &m), &m));
    }

    #[test]
    fn zero_up_picks_a_perpendicular() {
        let m = look_at([0.0; 3], [0.0, 0.0, 1.0], [0.0; 3]).unwrap();
        assert!(m.iter().flatten().all(|v| v.is_finite()));
        assert!(look_at([1.0; 3], [1.0; 3], [0.0, 1.0, 0.0]).is_err());
        assert!(look_at([0.0; 3], [0.0, 1.0, 0.0], [0.0, 1.0, 0.0]).is_err());
    }
}
