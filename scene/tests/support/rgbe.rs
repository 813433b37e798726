//! Radiance RGBE files for tests, written here so that environment tests need no image
//! files (the scene crate's and the integrator's environment tests share it).

/// A Radiance RGBE file (flat scanlines) of `width` x `height` texels `texel(x, y)`.
pub fn rgbe_file(width: u32, height: u32, texel: impl Fn(u32, u32) -> [f32; 3]) -> Vec<u8> {
    let mut out =
        format!("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y {height} +X {width}\n").into_bytes();
    for y in 0..height {
        for x in 0..width {
            let c = texel(x, y);
            let max = c[0].max(c[1]).max(c[2]);
            if max < 1e-32 {
                out.extend_from_slice(&[0, 0, 0, 0]);
                continue;
            }
            // max = m 2^e with m in [0.5, 1).
            let e = max.log2().floor() as i32 + 1;
            let scale = 256.0 / 2f32.powi(e);
            out.extend(c.map(|v| (v * scale).min(255.0) as u8));
            out.push((e + 128) as u8);
        }
    }
    out
}
