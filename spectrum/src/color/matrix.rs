/// A 3x3 matrix of `f64`, row-major, for colour transforms.
///
/// Deliberately tiny: colour needs products, the inverse and a diagonal, nothing more, and
/// keeping it here leaves this crate free of dependencies.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Mat3(pub [[f64; 3]; 3]);

impl Mat3 {
    /// The identity.
    pub const IDENTITY: Mat3 = Mat3([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);

    /// A diagonal matrix.
    pub fn diagonal(d: [f64; 3]) -> Self {
        Mat3([[d[0], 0.0, 0.0], [0.0, d[1], 0.0], [0.0, 0.0, d[2]]])
    }

    /// A matrix whose columns are `c`.
    pub fn from_columns(c: [[f64; 3]; 3]) -> Self {
        Mat3(std::array::from_fn(|r| std::array::from_fn(|k| c[k][r])))
    }

    /// Matrix times vector.
    pub fn apply(&self, v: [f64; 3]) -> [f64; 3] {
        self.0
            .map(|row| row[0] * v[0] + row[1] * v[1] + row[2] * v[2])
    }

    /// Matrix product `self * rhs`.
    pub fn mul(&self, rhs: &Mat3) -> Mat3 {
        Mat3(std::array::from_fn(|r| {
            std::array::from_fn(|c| (0..3).map(|k| self.0[r][k] * rhs.0[k][c]).sum())
        }))
    }

    /// The determinant.
    pub fn determinant(&self) -> f64 {
        let m = &self.0;
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    }

    /// The inverse by cofactors, or `None` when the matrix is singular or not finite.
    pub fn inverse(&self) -> Option<Mat3> {
        let m = &self.0;
        let det = self.determinant();
        let scale = m.iter().flatten().fold(0.0f64, |a, v| a.max(v.abs()));
        // Relative singularity test: det is cubic in the entries.
        if !det.is_finite() || det.abs() <= 1e-14 * scale * scale * scale {
            return None;
        }
        let cof = |r0: usize, r1: usize, c0: usize, c1: usize| {
            m[r0][c0] * m[r1][c1] - m[r0][c1] * m[r1][c0]
        };
        let adj = [
            [cof(1, 2, 1, 2), -cof(0, 2, 1, 2), cof(0, 1, 1, 2)],
            [-cof(1, 2, 0, 2), cof(0, 2, 0, 2), -cof(0, 1, 0, 2)],
            [cof(1, 2, 0, 1), -cof(0, 2, 0, 1), cof(0, 1, 0, 1)],
        ];
        Some(Mat3(adj.map(|row| row.map(|v| v / det))))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inverse_times_matrix_is_identity() {
        let m = Mat3([
            [0.4124, 0.3576, 0.1805],
            [0.2126, 0.7152, 0.0722],
            [0.0193, 0.1192, 0.9505],
        ]);
        let p = m.mul(&m.inverse().unwrap());
        for r in 0..3 {
            for c in 0..3 {
                let expected = if r == c { 1.0 } else { 0.0 };
                assert!((p.0[r][c] - expected).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn singular_matrix_has_no_inverse() {
        let m = Mat3([[1.0, 2.0, 3.0], [2.0, 4.0, 6.0], [0.0, 1.0, 1.0]]);
        assert!(m.inverse().is_none());
        assert!(Mat3([[0.0; 3]; 3]).inverse().is_none());
    }
}
