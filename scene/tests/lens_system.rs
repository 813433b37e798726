//! Real lens systems against closed forms: paraxial focal lengths equal the ABCD (ray
//! transfer) matrices' for a thick singlet and a cemented doublet at several wavelengths;
//! a thin BK7 singlet's focal shift from the C to the F line is f / V_d; an achromat's
//! is at least ten times smaller; and absurd prescriptions are clear errors.

use glam::DVec3;
use prism_scene::camera::system::{LensRay, LensSystem, parse_prescription};
use prism_spectrum::Spectrum;
use prism_spectrum::optics::{
    FRAUNHOFER_C_NM, FRAUNHOFER_D_NM, FRAUNHOFER_F_NM, abbe_number, named_glass,
};
use proptest::prelude::*;

fn n(glass: &str, lambda: f64) -> f64 {
    named_glass(glass).unwrap().ior.evaluate(lambda)
}

/// The effective focal length and back focal distance of a system of spherical surfaces
/// (radius, index after it, distance to the next surface) by paraxial ray-transfer
/// matrices in (y, n u): refraction [[1, 0], [-(n' - n) / R, 1]], transfer
/// [[1, d / n], [0, 1]].
fn abcd(surfaces: &[(f64, f64, f64)]) -> (f64, f64) {
    let mut m = [[1.0, 0.0], [0.0, 1.0]];
    let mul = |a: [[f64; 2]; 2], b: [[f64; 2]; 2]| {
        [
            [
                a[0][0] * b[0][0] + a[0][1] * b[1][0],
                a[0][0] * b[0][1] + a[0][1] * b[1][1],
            ],
            [
                a[1][0] * b[0][0] + a[1][1] * b[1][0],
                a[1][0] * b[0][1] + a[1][1] * b[1][1],
            ],
        ]
    };
    let mut n_before = 1.0;
    for (i, &(radius, n_after, d)) in surfaces.iter().enumerate() {
        m = mul([[1.0, 0.0], [-(n_after - n_before) / radius, 1.0]], m);
        if i + 1 < surfaces.len() {
            m = mul([[1.0, d / n_after], [0.0, 1.0]], m);
        }
        n_before = n_after;
    }
    let (a, c) = (m[0][0], m[1][0]);
    (-1.0 / c, -a / c)
}

fn singlet(glass: &str) -> String {
    format!("# biconvex singlet\n 100 4 1.5 30 {glass}\n -100 95 1 30\n")
}

/// A cemented achromat for 100 mm from BK7 and F2 by the thin-lens condition
/// phi_1 / V_1 + phi_2 / V_2 = 0: an equiconvex crown and a flint closing it.
fn achromat() -> (String, [f64; 3]) {
    let (v1, v2) = (
        abbe_number(&named_glass("bk7").unwrap().ior).unwrap(),
        abbe_number(&named_glass("f2").unwrap().ior).unwrap(),
    );
    let phi = 1.0 / 100.0;
    let (phi1, phi2) = (phi * v1 / (v1 - v2), -phi * v2 / (v1 - v2));
    let (n1, n2) = (n("bk7", FRAUNHOFER_D_NM), n("f2", FRAUNHOFER_D_NM));
    let r1 = 2.0 * (n1 - 1.0) / phi1;
    let r2 = -r1;
    // phi_2 = (n_2 - 1) (1 / r2 - 1 / r3)
    let r3 = 1.0 / (1.0 / r2 - phi2 / (n2 - 1.0));
    (
        format!("{r1} 3 1.5 30 bk7\n{r2} 1.5 1.6 30 f2\n{r3} 95 1 30\n"),
        [r1, r2, r3],
    )
}

#[test]
fn focal_lengths_equal_the_ray_transfer_matrices() {
    let lens = parse_prescription(&singlet("bk7")).unwrap();
    let (text, [r1, r2, r3]) = achromat();
    let doublet = parse_prescription(&text).unwrap();
    for lambda in [420.0, FRAUNHOFER_F_NM, 550.0, FRAUNHOFER_C_NM, 700.0] {
        let p = lens.paraxial(lambda).unwrap();
        let nb = n("bk7", lambda);
        let (efl, bfd) = abcd(&[(100.0, nb, 4.0), (-100.0, 1.0, 0.0)]);
        assert!(
            (p.efl_mm / efl - 1.0).abs() < 1e-4,
            "{lambda}: {} vs {efl}",
            p.efl_mm
        );
        assert!(
            (p.bfd_mm / bfd - 1.0).abs() < 1e-4,
            "{lambda}: {} vs {bfd}",
            p.bfd_mm
        );
        let p = doublet.paraxial(lambda).unwrap();
        let nf = n("f2", lambda);
        let (efl, bfd) = abcd(&[(r1, nb, 3.0), (r2, nf, 1.5), (r3, 1.0, 0.0)]);
        assert!(
            (p.efl_mm / efl - 1.0).abs() < 1e-4,
            "{lambda}: {} vs {efl}",
            p.efl_mm
        );
        assert!(
            (p.bfd_mm / bfd - 1.0).abs() < 1e-4,
            "{lambda}: {} vs {bfd}",
            p.bfd_mm
        );
    }
}

#[test]
fn a_singlet_shifts_focus_by_f_over_v_and_an_achromat_ten_times_less() {
    let thin = parse_prescription("200 1 1.5 20 bk7\n-200 190 1 20\n").unwrap();
    let f_d = thin.paraxial(FRAUNHOFER_D_NM).unwrap().efl_mm;
    let shift = thin.paraxial(FRAUNHOFER_C_NM).unwrap().efl_mm
        - thin.paraxial(FRAUNHOFER_F_NM).unwrap().efl_mm;
    let v_d = abbe_number(&named_glass("bk7").unwrap().ior).unwrap();
    assert!(
        (shift / (f_d / v_d) - 1.0).abs() < 0.02,
        "shift {shift} mm, f / V_d {}",
        f_d / v_d
    );
    let singlet = parse_prescription(&singlet("bk7")).unwrap();
    let bfd_shift = |l: &LensSystem| {
        (l.paraxial(FRAUNHOFER_C_NM).unwrap().bfd_mm - l.paraxial(FRAUNHOFER_F_NM).unwrap().bfd_mm)
            .abs()
    };
    let achromat = parse_prescription(&achromat().0).unwrap();
    let (s, a) = (bfd_shift(&singlet), bfd_shift(&achromat));
    assert!(
        a * 10.0 <= s,
        "achromat {a} mm against the singlet's {s} mm"
    );
}

#[test]
fn the_entrance_pupil_is_the_stop_seen_from_the_front() {
    // A stop of 10 mm in front of a singlet: the pupil is the stop itself.
    let lens = parse_prescription("0 5 0 10\n100 4 1.5 30 bk7\n-100 95 1 30\n").unwrap();
    let p = lens.paraxial(FRAUNHOFER_D_NM).unwrap();
    assert!(
        (p.entrance_pupil_mm - 10.0).abs() < 1e-6,
        "{}",
        p.entrance_pupil_mm
    );
    assert!((p.f_number - p.efl_mm / 10.0).abs() < 1e-9);
}

#[test]
fn absurd_prescriptions_are_clear_errors() {
    for (text, words) in [
        ("", "no interfaces"),
        ("100 4 1.5\n", "line 1: 3 columns"),
        ("100 4 1.5 30\n", "last interface"),
        ("100 -4 1.5 30\n-100 90 1 30\n", "line 1: thickness -4"),
        ("10 4 1.5 30\n-100 90 1 30\n", "radius 10 cannot be 30 wide"),
        ("100 4 1.5 0\n-100 90 1 30\n", "aperture diameter 0"),
        ("100 4 0.5 30\n-100 90 1 30\n", "index 0.5"),
        (
            "100 4 1.5 30 unobtainium\n-100 90 1 30\n",
            "glass 'unobtainium'",
        ),
        ("100 4 1.5 30 1.5:x\n-100 90 1 30\n", "ND:VD"),
        ("0 4 1.5 30 bk7\n-100 90 1 30\n", "stop"),
        ("100 nan 1.5 30\n-100 90 1 30\n", "thickness 'nan'"),
    ] {
        let e = parse_prescription(text).unwrap_err();
        assert!(e.contains(words), "{text:?}: {e}");
    }
}

proptest! {
    /// Rays at the rim, grazing and steep, through zero-thickness air gaps: each passes
    /// with a finite unit direction or is stopped; never NaN.
    #[test]
    fn lens_tracing_never_gives_nan(
        y in -20.0f64..20.0,
        x in -20.0f64..20.0,
        slope in (-3.0f64..3.0, -3.0f64..3.0),
        lambda in 300.0f64..900.0,
        gap in prop::sample::select(vec![0.0f64, 1e-9, 0.5]),
    ) {
        let text = format!("60 6 1.6 30 sf11\n-60 {gap} 1 30\n0 2 0 12\n80 5 1.5 28 bk7\n-80 60 1 28\n");
        let lens = parse_prescription(&text).unwrap();
        let ray = LensRay {
            origin: DVec3::new(x, y, -lens.length() - 5.0),
            direction: DVec3::new(slope.0, slope.1, 1.0).normalize(),
        };
        if let Some(out) = lens.trace_from_scene(ray, lambda) {
            prop_assert!(out.origin.is_finite() && out.direction.is_finite());
            prop_assert!((out.direction.length() - 1.0).abs() < 1e-9);
        }
    }
}

/// A thick singlet's principal planes sit where the closed form puts them: the rear one
/// f (n - 1) d / (n R1) in front of the rear vertex, the front one f (n - 1) d / (n R2)
/// behind the front vertex (signs as the radii's), and both focal points f from them.
#[test]
fn the_thick_lens_approximation_finds_the_principal_planes() {
    let lens = parse_prescription("50 12 1.5 40\n-80 70 1 40\n").unwrap();
    let thick = lens.thick_lens(FRAUNHOFER_D_NM).unwrap();
    let (n, d, r1, r2) = (1.5, 12.0, 50.0, -80.0);
    let f = 1.0 / ((n - 1.0) * (1.0 / r1 - 1.0 / r2 + (n - 1.0) * d / (n * r1 * r2)));
    let (front_vertex, rear_vertex) = (-82.0, -70.0);
    let rear_principal = rear_vertex - f * (n - 1.0) * d / (n * r1);
    let front_principal = front_vertex - f * (n - 1.0) * d / (n * r2);
    assert!(
        (thick.focal_length() - f).abs() < 1e-4 * f,
        "{} vs {f}",
        thick.focal_length()
    );
    assert!(
        (thick.rear_principal_z - rear_principal).abs() < 1e-3,
        "{thick:?} vs {rear_principal}"
    );
    assert!(
        (thick.front_principal_z - front_principal).abs() < 1e-3,
        "{thick:?} vs {front_principal}"
    );
    assert!((thick.front_principal_z - thick.front_focal_z - f).abs() < 1e-3);
}

/// Moving the film by `focus_shift` puts the image of an on-axis point at the distance
/// asked for on the film: a near-axis ray from it crosses the axis there.
#[test]
fn focusing_moves_the_film_to_the_image() {
    let (text, _) = achromat();
    let lens = parse_prescription(&text).unwrap();
    for distance in [400.0, 1000.0, 5000.0] {
        let shift = lens.focus_shift(distance, FRAUNHOFER_D_NM).unwrap();
        let ray = LensRay {
            origin: DVec3::new(0.0, 0.0, -distance),
            direction: DVec3::new(0.0, 1e-4, 1.0).normalize(),
        };
        let out = lens.trace_from_scene(ray, FRAUNHOFER_D_NM).unwrap();
        let crossing = out.origin.z - out.origin.y / out.direction.y * out.direction.z;
        assert!(
            (crossing - shift).abs() < 1e-3 * (1.0 + shift.abs()),
            "{distance}: image at {crossing}, film moved to {shift}"
        );
    }
    // Nearer than the front focal point there is no real image.
    assert!(lens.focus_shift(50.0, FRAUNHOFER_D_NM).is_none());
}

/// A lens with a small stop behind a wide front: from a film point, rays aimed at the
/// whole rear element mostly hit the stop; the exit-pupil bounds hold every ray that
/// passes (checked by aiming 20,000 at the rear element) and far fewer that do not.
#[test]
fn exit_pupil_bounds_hold_every_passing_ray_and_save_most_of_the_rest() {
    let lens = parse_prescription(
        "60 6 1.5 40 bk7\n-300 8 1 40\n0 8 0 8\n200 5 1.5 36 bk7\n-90 80 1 36\n",
    )
    .unwrap();
    let rear = lens.interfaces().last().unwrap();
    let (rear_z, radius) = (-rear.thickness, rear.aperture_radius);
    for film_x in [0.0, 6.0, 14.0] {
        let b = lens
            .exit_pupil(film_x, FRAUNHOFER_D_NM)
            .expect("some rays pass");
        let film = DVec3::new(film_x, 0.0, 0.0);
        let (mut passed, mut outside, mut aimed_in_bounds, mut passed_in_bounds) = (0, 0, 0, 0);
        let mut state = 12345u64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        for _ in 0..20_000 {
            let (r, a) = (radius * next().sqrt(), 2.0 * std::f64::consts::PI * next());
            let p = DVec3::new(r * a.cos(), r * a.sin(), rear_z);
            let inside = p.x >= b[0] && p.x <= b[2] && p.y >= b[1] && p.y <= b[3];
            let ray = LensRay {
                origin: film,
                direction: (p - film).normalize(),
            };
            let passes = lens.trace_from_film(ray, FRAUNHOFER_D_NM).is_some();
            if passes {
                passed += 1;
                outside += usize::from(!inside);
            }
            if inside {
                aimed_in_bounds += 1;
                passed_in_bounds += usize::from(passes);
            }
        }
        assert_eq!(
            outside, 0,
            "film x {film_x}: {outside} passing rays outside the bounds"
        );
        let disk_rate = passed as f64 / 20_000.0;
        let bounds_rate = passed_in_bounds as f64 / aimed_in_bounds.max(1) as f64;
        eprintln!(
            "film x {film_x} mm: {:.1}% of rays aimed at the rear element pass, {:.1}% of those aimed in the bounds",
            100.0 * disk_rate,
            100.0 * bounds_rate
        );
        assert!(
            bounds_rate > 3.0 * disk_rate,
            "film x {film_x}: {bounds_rate} in the bounds, {disk_rate} over the rear element"
        );
    }
}
