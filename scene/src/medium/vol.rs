//! Mitsuba's binary volume format (`.vol`, as Mitsuba 0.6 and 3 read and write it): the
//! bytes "VOL", version 3, an encoding (1: 32-bit floats), the resolution x, y, z and the
//! channel count as little-endian 32-bit integers, a bounding box as six floats (min x, y,
//! z, max x, y, z), then the values, channels fastest, then x, y, z.

use glam::{UVec3, Vec3};

use super::grid::Grid;

/// Bytes before the values.
const HEADER: usize = 48;

/// Reads a one-channel `.vol` file's field, placed on the file's bounding box. Every
/// malformation is an error naming what is wrong.
pub fn read_vol(bytes: &[u8]) -> Result<Grid, String> {
    if bytes.len() < HEADER || &bytes[..3] != b"VOL" {
        return Err("not a .vol file (it must start with \"VOL\" and a 48-byte header)".into());
    }
    if bytes[3] != 3 {
        return Err(format!(".vol version {} (prism reads version 3)", bytes[3]));
    }
    let int = |at: usize| i32::from_le_bytes(bytes[at..at + 4].try_into().expect("4 bytes"));
    let float = |at: usize| f32::from_le_bytes(bytes[at..at + 4].try_into().expect("4 bytes"));
    let encoding = int(4);
    if encoding != 1 {
        return Err(format!(
            ".vol encoding {encoding} (prism reads 1, 32-bit floats)"
        ));
    }
    let (x, y, z, channels) = (int(8), int(12), int(16), int(20));
    if x <= 0 || y <= 0 || z <= 0 {
        return Err(format!("a .vol grid of {x} x {y} x {z} voxels"));
    }
    if channels != 1 {
        return Err(format!(
            "the .vol file has {channels} channels per voxel (a density grid has 1)"
        ));
    }
    let count = x as u64 * y as u64 * z as u64;
    let expected = HEADER as u64 + 4 * count;
    if bytes.len() as u64 != expected {
        return Err(format!(
            "the .vol file is {} bytes; a {x} x {y} x {z} grid of floats takes {expected}",
            bytes.len()
        ));
    }
    let min = Vec3::new(float(24), float(28), float(32));
    let max = Vec3::new(float(36), float(40), float(44));
    let values = bytes[HEADER..]
        .chunks_exact(4)
        .map(|b| f32::from_le_bytes(b.try_into().expect("4 bytes")))
        .collect();
    Grid::new(UVec3::new(x as u32, y as u32, z as u32), min, max, values)
}

/// Writes `values` (x fastest) over `min`-`max` as a one-channel `.vol` file.
pub fn write_vol(resolution: UVec3, min: Vec3, max: Vec3, values: &[f32]) -> Vec<u8> {
    let mut out = Vec::with_capacity(HEADER + 4 * values.len());
    out.extend_from_slice(b"VOL");
    out.push(3);
    for v in [
        1,
        resolution.x as i32,
        resolution.y as i32,
        resolution.z as i32,
        1,
    ] {
        out.extend_from_slice(&v.to_le_bytes());
    }
    for v in min.to_array().into_iter().chain(max.to_array()) {
        out.extend_from_slice(&v.to_le_bytes());
    }
    for v in values {
        out.extend_from_slice(&v.to_le_bytes());
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// What Mitsuba 3 wrote for `VolumeGrid(np.arange(24).reshape(2, 3, 4, 1))`: x fastest,
    /// resolution (4, 3, 2), the unit box.
    #[test]
    fn reads_what_mitsuba_writes() {
        let values: Vec<f32> = (0..24).map(|v| v as f32).collect();
        let bytes = write_vol(UVec3::new(4, 3, 2), Vec3::ZERO, Vec3::ONE, &values);
        assert_eq!(bytes.len(), 144);
        assert_eq!(&bytes[..4], b"VOL\x03");
        let grid = read_vol(&bytes).unwrap();
        assert_eq!(grid.resolution(), UVec3::new(4, 3, 2));
        // Voxel (x 1, y 2, z 1) = 1 + 4 * 2 + 12 * 1 = 21, at its centre.
        let p = Vec3::new(1.5 / 4.0, 2.5 / 3.0, 1.5 / 2.0);
        assert!((grid.lookup(p) - 21.0).abs() < 1e-5);
    }

    #[test]
    fn malformed_files_are_errors() {
        let good = write_vol(UVec3::ONE, Vec3::ZERO, Vec3::ONE, &[1.0]);
        assert!(read_vol(&good).is_ok());
        assert!(read_vol(b"VOL").is_err());
        assert!(read_vol(&good[..good.len() - 1]).is_err());
        let mut nan = good.clone();
        nan[48..52].copy_from_slice(&f32::NAN.to_le_bytes());
        assert!(read_vol(&nan).unwrap_err().contains("NaN"));
        let mut version = good.clone();
        version[3] = 2;
        assert!(read_vol(&version).is_err());
        let mut channels = good.clone();
        channels[20] = 3;
        assert!(read_vol(&channels).is_err());
        let mut flat = good;
        flat[36..40].copy_from_slice(&0.0f32.to_le_bytes());
        assert!(read_vol(&flat).is_err());
    }
}
