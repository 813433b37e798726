//! A film's AOV sums: per pixel, what the feature pass and the radiance's samples add,
//! kept in f64 like the radiance's sums and merged, checkpointed and written with them.

use prism_spectrum::color::{AdaptationMethod, Mat3, RgbColorSpace, adaptation_matrix};
use prism_spectrum::colorimetry::{WhitePoint, Xyz};

use prism_spectrum::saturating_f32;

use crate::film::aov::{Aov, Aovs};

/// "No sample yet" for a pixel's material: an index above any sample's (finite, so that
/// accumulation files, which refuse non-finite sums, keep it).
const NO_SAMPLE: f64 = 1.8e19;

/// Per-pixel AOV sums; each vector is empty unless its AOV is asked for.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct AovSums {
    set: Aovs,
    /// Albedo as XYZ relative to the equal-energy white (a white reflectance of 1 is
    /// (1, 1, 1)), summed over samples.
    pub(crate) albedo: Vec<[f64; 3]>,
    pub(crate) normal: Vec<[f64; 3]>,
    pub(crate) depth: Vec<f64>,
    pub(crate) position: Vec<[f64; 3]>,
    /// Samples whose camera ray met a surface (depth's and position's count).
    pub(crate) hits: Vec<f64>,
    /// (the lowest sample index seen, 1 + its material index or 0).
    pub(crate) material: Vec<[f64; 2]>,
    /// The second replicate's sums (`Replicas`: odd samples, scrambled apart from the
    /// even ones): the colour of its samples and light-path splats, and its samples.
    pub(crate) replica: Vec<[f64; 4]>,
}

/// The mutable per-pixel sums of one row (empty slices for AOVs not asked for).
pub(crate) struct AovRow<'a> {
    pub albedo: &'a mut [[f64; 3]],
    pub normal: &'a mut [[f64; 3]],
    pub depth: &'a mut [f64],
    pub position: &'a mut [[f64; 3]],
    pub hits: &'a mut [f64],
    pub material: &'a mut [[f64; 2]],
}

fn zeros<T: Clone + Default>(on: bool, pixels: usize) -> Vec<T> {
    if on {
        vec![T::default(); pixels]
    } else {
        Vec::new()
    }
}

fn add_all<const K: usize>(a: &mut [[f64; K]], b: &[[f64; K]]) {
    for (x, y) in a.iter_mut().zip(b) {
        for (p, q) in x.iter_mut().zip(y) {
            *p += q;
        }
    }
}

fn chunks<T>(v: &mut [T], width: usize, rows: usize) -> Vec<&mut [T]> {
    if v.is_empty() {
        (0..rows).map(|_| -> &mut [T] { &mut [] }).collect()
    } else {
        v.chunks_mut(width).collect()
    }
}

impl AovSums {
    /// Zero sums for `set` over `pixels` pixels.
    pub(crate) fn new(set: Aovs, pixels: usize) -> Self {
        let hits = set.has(Aov::Depth) || set.has(Aov::Position);
        Self {
            set,
            albedo: zeros(set.has(Aov::Albedo), pixels),
            normal: zeros(set.has(Aov::Normal), pixels),
            depth: zeros(set.has(Aov::Depth), pixels),
            position: zeros(set.has(Aov::Position), pixels),
            hits: zeros(hits, pixels),
            material: if set.has(Aov::MaterialId) {
                vec![[NO_SAMPLE, 0.0]; pixels]
            } else {
                Vec::new()
            },
            replica: zeros(set.has(Aov::Variance), pixels),
        }
    }

    /// Every sum back to zero (and every material to none), the buffers kept.
    pub(crate) fn clear(&mut self) {
        self.albedo.fill([0.0; 3]);
        self.normal.fill([0.0; 3]);
        self.depth.fill(0.0);
        self.position.fill([0.0; 3]);
        self.hits.fill(0.0);
        self.material.fill([NO_SAMPLE, 0.0]);
        self.replica.fill([0.0; 4]);
    }

    /// The AOVs these sums hold.
    pub fn set(&self) -> Aovs {
        self.set
    }

    /// The feature pass's sums cut into rows of `width` pixels.
    pub(crate) fn rows_mut(&mut self, width: usize, rows: usize) -> Vec<AovRow<'_>> {
        let mut albedo = chunks(&mut self.albedo, width, rows).into_iter();
        let mut normal = chunks(&mut self.normal, width, rows).into_iter();
        let mut depth = chunks(&mut self.depth, width, rows).into_iter();
        let mut position = chunks(&mut self.position, width, rows).into_iter();
        let mut hits = chunks(&mut self.hits, width, rows).into_iter();
        let mut material = chunks(&mut self.material, width, rows).into_iter();
        (0..rows)
            .filter_map(|_| {
                Some(AovRow {
                    albedo: albedo.next()?,
                    normal: normal.next()?,
                    depth: depth.next()?,
                    position: position.next()?,
                    hits: hits.next()?,
                    material: material.next()?,
                })
            })
            .collect()
    }

    /// Adds another film's sums (sample ranges rendered apart).
    pub(crate) fn merge(&mut self, other: &AovSums) -> Result<(), String> {
        if self.set != other.set {
            return Err(format!(
                "films differ in their AOVs: '{}' and '{}'",
                self.set, other.set
            ));
        }
        add_all(&mut self.albedo, &other.albedo);
        add_all(&mut self.normal, &other.normal);
        add_all(&mut self.position, &other.position);
        add_all(&mut self.replica, &other.replica);
        for (a, b) in self.depth.iter_mut().zip(&other.depth) {
            *a += b;
        }
        for (a, b) in self.hits.iter_mut().zip(&other.hits) {
            *a += b;
        }
        for (a, b) in self.material.iter_mut().zip(&other.material) {
            if b[0] < a[0] {
                *a = *b;
            }
        }
        Ok(())
    }

    /// The replicate's colours transformed as the film's are by `m` (white balance).
    pub(crate) fn adapt(&mut self, m: &Mat3) {
        for s in &mut self.replica {
            let c = m.apply([s[0], s[1], s[2]]);
            s[..3].copy_from_slice(&c);
        }
    }

    /// Named columns of every sum (for accumulation files), in a fixed order.
    #[cfg(feature = "exr")]
    pub(crate) fn columns(&self) -> Vec<(String, Vec<f64>)> {
        let mut out = Vec::new();
        let mut put = |name: &str, values: Vec<f64>| {
            if !values.is_empty() {
                out.push((name.to_string(), values));
            }
        };
        for k in 0..3 {
            put(
                &format!("AovAlbedo{k}"),
                self.albedo.iter().map(|v| v[k]).collect(),
            );
            put(
                &format!("AovNormal{k}"),
                self.normal.iter().map(|v| v[k]).collect(),
            );
            put(
                &format!("AovPosition{k}"),
                self.position.iter().map(|v| v[k]).collect(),
            );
        }
        put("AovDepth", self.depth.clone());
        put("AovHits", self.hits.clone());
        for k in 0..2 {
            put(
                &format!("AovMaterial{k}"),
                self.material.iter().map(|v| v[k]).collect(),
            );
        }
        for k in 0..4 {
            put(
                &format!("AovReplica{k}"),
                self.replica.iter().map(|v| v[k]).collect(),
            );
        }
        out
    }

    /// Sums for `set` over `pixels` pixels read back from [`AovSums::columns`]' columns
    /// (`column` finds one by name); an error names a missing or short column.
    #[cfg(feature = "exr")]
    pub(crate) fn from_columns(
        set: Aovs,
        pixels: usize,
        column: &mut dyn FnMut(&str) -> Option<Vec<f64>>,
    ) -> Result<Self, String> {
        let mut sums = Self::new(set, pixels);
        let mut read = |name: &str| {
            column(name)
                .filter(|v| v.len() == pixels)
                .ok_or_else(|| format!("AOV channel {name} missing or of the wrong size"))
        };
        fn fill<const K: usize>(v: &mut [[f64; K]], k: usize, values: Vec<f64>) {
            for (p, x) in v.iter_mut().zip(values) {
                p[k] = x;
            }
        }
        for k in 0..3 {
            if !sums.albedo.is_empty() {
                fill(&mut sums.albedo, k, read(&format!("AovAlbedo{k}"))?);
            }
            if !sums.normal.is_empty() {
                fill(&mut sums.normal, k, read(&format!("AovNormal{k}"))?);
            }
            if !sums.position.is_empty() {
                fill(&mut sums.position, k, read(&format!("AovPosition{k}"))?);
            }
        }
        if !sums.depth.is_empty() {
            sums.depth = read("AovDepth")?;
        }
        if !sums.hits.is_empty() {
            sums.hits = read("AovHits")?;
        }
        if !sums.material.is_empty() {
            for k in 0..2 {
                fill(&mut sums.material, k, read(&format!("AovMaterial{k}"))?);
            }
        }
        if !sums.replica.is_empty() {
            for k in 0..4 {
                fill(&mut sums.replica, k, read(&format!("AovReplica{k}"))?);
            }
        }
        Ok(sums)
    }

    /// The images of the AOVs asked for, as EXR channels (`layer.channel`, values
    /// row-major): `samples` samples per pixel, colours in `space`, the colour sums
    /// `xyz` (the radiance's, for the variance).
    pub(crate) fn images(
        &self,
        samples: u64,
        space: &RgbColorSpace,
        xyz: &[[f64; 3]],
    ) -> Vec<(String, Vec<f32>)> {
        let n = samples.max(1) as f64;
        let mut out = Vec::new();
        fn put3(
            out: &mut Vec<(String, Vec<f32>)>,
            layer: &str,
            names: [&str; 3],
            values: Vec<[f64; 3]>,
        ) {
            for (k, name) in names.iter().enumerate() {
                let channel = values.iter().map(|v| saturating_f32(v[k])).collect();
                out.push((format!("{layer}.{name}"), channel));
            }
        }
        if self.set.has(Aov::Albedo) {
            let to_white =
                adaptation_matrix(WhitePoint::E, space.white(), AdaptationMethod::Bradford);
            let rgb = self
                .albedo
                .iter()
                .map(|s| {
                    let xyz = to_white.apply(s.map(|v| v / n));
                    space.xyz_to_rgb(Xyz::new(xyz[0], xyz[1], xyz[2]))
                })
                .collect();
            put3(&mut out, "albedo", ["R", "G", "B"], rgb);
        }
        if self.set.has(Aov::Normal) {
            let normal = self.normal.iter().map(|s| s.map(|v| v / n)).collect();
            put3(&mut out, "normal", ["X", "Y", "Z"], normal);
        }
        let per_hit = |sum: f64, hits: f64| if hits > 0.0 { sum / hits } else { 0.0 };
        if self.set.has(Aov::Depth) {
            let depth = self.depth.iter().zip(&self.hits);
            let values = depth
                .map(|(d, h)| saturating_f32(per_hit(*d, *h)))
                .collect();
            out.push(("depth.Z".to_string(), values));
        }
        if self.set.has(Aov::Position) {
            let position = self.position.iter().zip(&self.hits);
            let values = position.map(|(p, h)| p.map(|v| per_hit(v, *h))).collect();
            put3(&mut out, "position", ["X", "Y", "Z"], values);
        }
        if self.set.has(Aov::MaterialId) {
            let values = self.material.iter().map(|m| m[1] as f32).collect();
            out.push(("material_id.ID".to_string(), values));
        }
        if self.set.has(Aov::Variance) {
            let to_rgb = space.xyz_to_rgb_matrix();
            let values = self
                .replica
                .iter()
                .zip(xyz)
                .map(|(r, s)| variance_of_mean(r, s, n, &to_rgb))
                .collect();
            put3(&mut out, "variance", ["R", "G", "B"], values);
        }
        out
    }
}

impl AovSums {
    /// The relative MSE the image's mean is expected to have, from the variance AOV: the
    /// mean over pixels and X, Y, Z of Var(mean) / (mean^2 + 0.01), the measure `prism
    /// compare` reports against a reference. None without the variance AOV or below two
    /// samples.
    pub(crate) fn estimated_relmse(&self, samples: u64, xyz: &[[f64; 3]]) -> Option<f64> {
        if self.replica.is_empty() || samples < 2 || xyz.is_empty() {
            return None;
        }
        let n = samples as f64;
        let total: f64 = self
            .replica
            .iter()
            .zip(xyz)
            .map(|(r, s)| {
                let variance = variance_of_mean(r, s, n, &Mat3::IDENTITY);
                (0..3)
                    .map(|k| {
                        let mean = s[k] / n;
                        variance[k] / (mean * mean + 0.01)
                    })
                    .sum::<f64>()
            })
            .sum();
        let value = total / (3 * xyz.len()) as f64;
        value.is_finite().then_some(value)
    }
}

/// Per RGB channel, the variance of a pixel's mean of `n` samples whose colours sum to
/// `sum`, from the two replicates' means (`replica`: the second's colour sum and
/// samples; the first's are the rest). With A and B the replicates' means over n_a and
/// n_b samples, the pixel is (n_a A + n_b B) / n, and since A and B are independent
/// and unbiased, E[(A - B)^2] = Var A + Var B: for variances inversely proportional to
/// the samples, Var(pixel) = n_a n_b / n^2 E[(A - B)^2]. Carried into RGB by `to_rgb`
/// (a linear map of A - B); 0 until both replicates have a sample.
fn variance_of_mean(replica: &[f64; 4], sum: &[f64; 3], n: f64, to_rgb: &Mat3) -> [f64; 3] {
    let n_b = replica[3];
    let n_a = n - n_b;
    if n_a < 1.0 || n_b < 1.0 {
        return [0.0; 3];
    }
    let difference: [f64; 3] =
        std::array::from_fn(|k| (sum[k] - replica[k]) / n_a - replica[k] / n_b);
    let weight = n_a * n_b / (n * n);
    to_rgb.apply(difference).map(|d| d * d * weight)
}

#[cfg(test)]
mod tests {
    use super::*;
    use prism_spectrum::color::RgbSpaceId;

    #[test]
    fn variance_of_two_replicates() {
        // Replicate means 1 (first, 2 samples summing to 2) and 3 (second, 2 samples
        // summing to 6): pixel mean 2, Var = 2 * 2 / 16 * (1 - 3)^2 = 1.
        let replica = [6.0, 6.0, 6.0, 2.0];
        let sum = [8.0; 3];
        let v = variance_of_mean(&replica, &sum, 4.0, &Mat3::IDENTITY);
        for c in v {
            assert!((c - 1.0).abs() < 1e-12, "{v:?}");
        }
        // Not defined until both replicates have a sample.
        assert_eq!(
            variance_of_mean(&[0.0; 4], &[1.0; 3], 1.0, &Mat3::IDENTITY),
            [0.0; 3]
        );
        // In RGB, the squared difference of the replicates' RGB means.
        let space = RgbSpaceId::Srgb.space();
        let to_rgb = space.xyz_to_rgb_matrix();
        let (a, b) = ([0.2, 0.3, 0.1], [0.5, 0.4, 0.9]);
        let replica = [b[0] * 3.0, b[1] * 3.0, b[2] * 3.0, 3.0];
        let sum: [f64; 3] = std::array::from_fn(|k| a[k] * 3.0 + b[k] * 3.0);
        let got = variance_of_mean(&replica, &sum, 6.0, &to_rgb);
        let (ra, rb) = (to_rgb.apply(a), to_rgb.apply(b));
        for k in 0..3 {
            let want = (ra[k] - rb[k]).powi(2) / 4.0;
            assert!((got[k] - want).abs() < 1e-12, "{k}: {} vs {want}", got[k]);
        }
    }

    #[test]
    fn merging_keeps_the_lowest_samples_material() {
        let set = "material_id,depth".parse().unwrap();
        let mut a = AovSums::new(set, 2);
        let mut b = AovSums::new(set, 2);
        a.material = vec![[4.0, 2.0], [4.0, 1.0]];
        b.material = vec![[0.0, 3.0], [NO_SAMPLE, 0.0]];
        b.depth = vec![1.0, 2.0];
        a.merge(&b).unwrap();
        assert_eq!(a.material, vec![[0.0, 3.0], [4.0, 1.0]]);
        assert_eq!(a.depth, vec![1.0, 2.0]);
        let other = AovSums::new("albedo".parse().unwrap(), 2);
        assert!(a.merge(&other).unwrap_err().contains("AOVs"));
    }
}
