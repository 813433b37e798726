use super::{PiecewiseConstant1D, Sample1D};
use crate::error::SamplingError;

/// A sample of a [`PiecewiseConstant2D`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample2D {
    /// The point, in `[0, 1)^2` scaled to the domain.
    pub point: [f64; 2],
    /// Its density with respect to area in the domain.
    pub pdf: f64,
}

/// A piecewise-constant 2D density on a `width x height` grid over a rectangle, sampled
/// as a marginal distribution over rows and a conditional distribution within the chosen
/// row (*PBR* 4th ed., §A.5.2): the tool for environment maps.
#[derive(Debug, Clone, PartialEq)]
pub struct PiecewiseConstant2D {
    conditionals: Vec<Option<PiecewiseConstant1D>>,
    marginal: PiecewiseConstant1D,
    domain: [[f64; 2]; 2],
}

impl PiecewiseConstant2D {
    /// A distribution proportional to `values` given row by row (`height` rows of `width`)
    /// over `[x0, x1) x [y0, y1)`.
    pub fn new(
        values: &[f64],
        width: usize,
        height: usize,
        domain: [[f64; 2]; 2],
    ) -> Result<Self, SamplingError> {
        if width == 0 || height == 0 || width.checked_mul(height) != Some(values.len()) {
            return Err(SamplingError::InvalidParameter(format!(
                "{} values do not form a {width} x {height} grid",
                values.len()
            )));
        }
        crate::error::validate(values)?;
        let [[x0, x1], [y0, y1]] = domain;
        let mut conditionals = Vec::with_capacity(height);
        let mut row_integrals = Vec::with_capacity(height);
        for row in values.chunks(width) {
            match PiecewiseConstant1D::new(row, x0, x1) {
                Ok(d) => {
                    row_integrals.push(d.integral());
                    conditionals.push(Some(d));
                }
                Err(SamplingError::AllZero) => {
                    row_integrals.push(0.0);
                    conditionals.push(None);
                }
                Err(e) => return Err(e),
            }
        }
        let marginal = PiecewiseConstant1D::new(&row_integrals, y0, y1)?;
        Ok(Self {
            conditionals,
            marginal,
            domain,
        })
    }

    /// A point with density proportional to the function; `u` components are clamped
    /// into [0, 1).
    pub fn sample(&self, u: [f64; 2]) -> Sample2D {
        let Sample1D {
            value: y,
            pdf: pdf_y,
            bin,
        } = self.marginal.sample(u[1]);
        // The marginal never picks a zero row, so its conditional exists.
        match &self.conditionals[bin] {
            Some(row) => {
                let s = row.sample(u[0]);
                Sample2D {
                    point: [s.value, y],
                    pdf: s.pdf * pdf_y,
                }
            }
            None => Sample2D {
                point: [self.domain[0][0], y],
                pdf: 0.0,
            },
        }
    }

    /// The density at `point` (0 outside the domain).
    pub fn pdf(&self, point: [f64; 2]) -> f64 {
        let pdf_y = self.marginal.pdf(point[1]);
        if pdf_y == 0.0 {
            return 0.0;
        }
        let [_, [y0, y1]] = self.domain;
        let rows = self.conditionals.len();
        let row = (((point[1] - y0) / (y1 - y0) * rows as f64) as usize).min(rows - 1);
        self.conditionals[row]
            .as_ref()
            .map_or(0.0, |c| c.pdf(point[0]) * pdf_y)
    }
}
