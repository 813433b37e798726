//! Mitsuba's binary volume format (`.vol`, as Mitsuba 0.6 and 3 read and write it): the
//! bytes "VOL", version 3, an encoding (1: 32-bit floats), the resolution x, y, z and the
//! channel count as little-endian 32-bit integers, a bounding box as six floats (min x, y,
//! z, max x, y, z), then the values, channels fastest, then x, y, z.

use glam::{UVec3, Vec3};

use super::grid::Grid;

/// Bytes before the values.
const HEADER: usize = 48;

/// The most values (voxels times channels) a file may declare: 1 GiB of floats, as
/// `.vdb` files are held to. Checked before anything is allocated.
const MAX_VALUES: u64 = 1 << 28;

/// A `.vol` file's contents.
#[derive(Debug, Clone, PartialEq)]
pub struct VolFile {
    /// Voxels along x, y and z (each at least 1).
    pub resolution: UVec3,
    /// Values per voxel (Mitsuba writes 1, 3 or 6).
    pub channels: u32,
    /// The bounding box the file gives (Mitsuba uses it only with `use_grid_bbox`; it may
    /// be empty).
    pub min: Vec3,
    /// Its other corner.
    pub max: Vec3,
    /// The values, channels fastest, then x, y, z.
    pub values: Vec<f32>,
}

/// Parses a `.vol` file of any channel count. Every malformation is an error naming what
/// is wrong; sizes the bytes cannot hold are refused before anything is allocated.
pub fn parse_vol(bytes: &[u8]) -> Result<VolFile, String> {
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
    if x <= 0 || y <= 0 || z <= 0 || channels <= 0 {
        return Err(format!(
            "a .vol grid of {x} x {y} x {z} voxels of {channels} channels"
        ));
    }
    // Each factor is below 2^31: no product of two overflows, and the third is checked.
    let count = (x as u64 * y as u64)
        .checked_mul(z as u64)
        .and_then(|v| v.checked_mul(channels as u64))
        .filter(|&v| v <= MAX_VALUES)
        .ok_or_else(|| {
            format!(
                "a .vol grid of {x} x {y} x {z} voxels of {channels} channels is more than prism reads ({MAX_VALUES} values)"
            )
        })?;
    let expected = HEADER as u64 + 4 * count;
    if bytes.len() as u64 != expected {
        return Err(format!(
            "the .vol file is {} bytes; a {x} x {y} x {z} grid of {channels} floats per voxel takes {expected}",
            bytes.len()
        ));
    }
    let values = bytes[HEADER..]
        .chunks_exact(4)
        .map(|b| f32::from_le_bytes(b.try_into().expect("4 bytes")))
        .collect();
    Ok(VolFile {
        resolution: UVec3::new(x as u32, y as u32, z as u32),
        channels: channels as u32,
        min: Vec3::new(float(24), float(28), float(32)),
        max: Vec3::new(float(36), float(40), float(44)),
        values,
    })
}

/// Reads a one-channel `.vol` file's field, placed on the file's bounding box. Every
/// malformation is an error naming what is wrong.
pub fn read_vol(bytes: &[u8]) -> Result<Grid, String> {
    let file = parse_vol(bytes)?;
    if file.channels != 1 {
        return Err(format!(
            "the .vol file has {} channels per voxel (a density grid has 1)",
            file.channels
        ));
    }
    Grid::new(file.resolution, file.min, file.max, file.values)
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
        // Only placing a grid on the file's box needs the box: a parse keeps it as it is.
        assert!(parse_vol(&flat).is_ok());
    }

    /// Headers that declare more than the file holds, up to sizes whose product overflows
    /// 64 bits, are one-line errors before anything is allocated.
    #[test]
    fn hostile_sizes_are_refused_before_allocating() {
        let good = write_vol(UVec3::ONE, Vec3::ZERO, Vec3::ONE, &[1.0]);
        for (x, y, z, c) in [
            (i32::MAX, i32::MAX, i32::MAX, i32::MAX),
            (1 << 20, 1 << 20, 1 << 20, 1),
            (1024, 1024, 1024, 3),
            (2, 1, 1, 1),
            (1, 1, 1, 0),
            (-1, 1, 1, 1),
        ] {
            let mut bytes = good.clone();
            for (at, v) in [(8, x), (12, y), (16, z), (20, c)] {
                bytes[at..at + 4].copy_from_slice(&v.to_le_bytes());
            }
            let e = parse_vol(&bytes).unwrap_err();
            assert!(!e.contains('\n'), "{e}");
            assert!(e.contains("voxels") || e.contains("bytes"), "{e}");
        }
    }

    /// Three channels per voxel are read in Mitsuba's order: channels fastest, then x.
    #[test]
    fn reads_channels_fastest() {
        let mut bytes = write_vol(UVec3::new(2, 1, 1), Vec3::ZERO, Vec3::ONE, &[0.0; 6]);
        bytes[20..24].copy_from_slice(&3i32.to_le_bytes());
        for (k, v) in (0..6).map(|k| (k, k as f32)) {
            bytes[48 + 4 * k..52 + 4 * k].copy_from_slice(&v.to_le_bytes());
        }
        let file = parse_vol(&bytes).unwrap();
        assert_eq!((file.channels, file.resolution), (3, UVec3::new(2, 1, 1)));
        assert_eq!(file.values, vec![0.0, 1.0, 2.0, 3.0, 4.0, 5.0]);
        assert!(read_vol(&bytes).unwrap_err().contains("3 channels"));
    }
}
