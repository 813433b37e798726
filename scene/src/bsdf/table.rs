//! Bilinear lookups in the albedo tables the layered lobes keep.

/// The value of a row-major `width`-wide table at continuous indices (`x`, `y`), clamped
/// to the table and interpolated bilinearly.
pub(crate) fn bilinear(table: &[f32], width: usize, x: f32, y: f32) -> f32 {
    let height = table.len() / width;
    let x = x.clamp(0.0, (width - 1) as f32);
    let y = y.clamp(0.0, (height - 1) as f32);
    let (i, j) = ((x as usize).min(width - 2), (y as usize).min(height - 2));
    let (tx, ty) = (x - i as f32, y - j as f32);
    let at = |i: usize, j: usize| table[j * width + i];
    let lower = at(i, j) * (1.0 - tx) + at(i + 1, j) * tx;
    let upper = at(i, j + 1) * (1.0 - tx) + at(i + 1, j + 1) * tx;
    lower * (1.0 - ty) + upper * ty
}
