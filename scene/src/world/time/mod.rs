//! Time: when light sources shine (schedules) and how long phosphorescent materials glow
//! after absorbing (decay laws), for renders of one instant of the scene's clock
//! (`--at`). Without an instant every source has always been on: the steady state, which
//! is the image a scene without schedules always had.

use std::sync::Arc;

use prism_sampling::decay::Decay;

/// When a source shines: disjoint time intervals [start, end) in seconds, in order; an
/// end may be infinite ("until further notice").
#[derive(Debug, Clone, PartialEq)]
pub struct Schedule {
    intervals: Vec<(f64, f64)>,
}

impl Schedule {
    /// The schedule of `intervals` (start, end): starts finite, each end after its start
    /// (or infinite), in order and not overlapping. The error says which rule failed.
    pub fn new(intervals: Vec<(f64, f64)>) -> Result<Self, String> {
        if intervals.is_empty() {
            return Err("a schedule needs at least one [start, end] interval".into());
        }
        let mut previous_end = f64::NEG_INFINITY;
        for (i, &(start, end)) in intervals.iter().enumerate() {
            if !start.is_finite() {
                return Err(format!(
                    "interval {i} starts at {start}, not a time in seconds"
                ));
            }
            if end.is_nan() || end <= start {
                return Err(format!(
                    "interval {i} [{start}, {end}] is reversed or empty (end must come after start)"
                ));
            }
            if start < previous_end {
                return Err(format!(
                    "interval {i} starts at {start}, before the previous one ends ({previous_end}): intervals must be in order and not overlap"
                ));
            }
            previous_end = end;
        }
        Ok(Self { intervals })
    }

    /// The intervals.
    pub fn intervals(&self) -> &[(f64, f64)] {
        &self.intervals
    }

    /// Whether the source shines at time `t`.
    pub fn on(&self, t: f64) -> bool {
        self.intervals
            .iter()
            .any(|&(start, end)| start <= t && t < end)
    }
}

/// A scene's timing: per light its schedule (None: always on), per material its decay
/// law (None: instantaneous), and when any source shines (the union of the schedules),
/// where a phosphor's absorbed light can come from.
#[derive(Debug, Clone, Default)]
pub struct Timeline {
    schedules: Vec<Option<Arc<Schedule>>>,
    decays: Vec<Option<Arc<Decay>>>,
    union: Vec<(f64, f64)>,
}

impl Timeline {
    /// The timing of a scene with `lights` lights, given schedules by light index and
    /// decays by material index (indices past the ends mean none).
    pub fn new(
        lights: usize,
        schedules: Vec<(usize, Arc<Schedule>)>,
        decays: Vec<(usize, Arc<Decay>)>,
    ) -> Self {
        let mut by_light = vec![None; lights];
        for (i, s) in schedules {
            if let Some(slot) = by_light.get_mut(i) {
                *slot = Some(s);
            }
        }
        let mut by_material = Vec::new();
        for (m, d) in decays {
            if by_material.len() <= m {
                by_material.resize(m + 1, None);
            }
            by_material[m] = Some(d);
        }
        let union = union_of(&by_light);
        Self {
            schedules: if by_light.iter().any(Option::is_some) {
                by_light
            } else {
                Vec::new()
            },
            decays: by_material,
            union,
        }
    }

    /// Whether anything in the scene depends on time (a schedule or a decay).
    pub fn is_timed(&self) -> bool {
        !self.schedules.is_empty() || self.decays.iter().any(Option::is_some)
    }

    /// Whether light `index` shines at time `t`.
    pub fn on(&self, index: u32, t: f64) -> bool {
        match self.schedules.get(index as usize) {
            Some(Some(s)) => s.on(t),
            _ => true,
        }
    }

    /// The schedule of light `index`, if it has one.
    pub fn schedule(&self, index: u32) -> Option<&Schedule> {
        self.schedules.get(index as usize)?.as_deref()
    }

    /// The decay law of material `index`, if it is phosphorescent.
    pub fn decay(&self, index: u32) -> Option<&Decay> {
        self.decays.get(index as usize)?.as_deref()
    }

    /// When some source shines: the union of the schedules (everything, if any light has
    /// none).
    pub fn any_on(&self) -> &[(f64, f64)] {
        &self.union
    }
}

/// The union of the lights' schedules, merged and in order; all time when a light has no
/// schedule (or there are no lights with schedules).
fn union_of(schedules: &[Option<Arc<Schedule>>]) -> Vec<(f64, f64)> {
    if schedules.is_empty() || schedules.iter().any(Option::is_none) {
        return vec![(f64::NEG_INFINITY, f64::INFINITY)];
    }
    let mut all: Vec<(f64, f64)> = schedules
        .iter()
        .flatten()
        .flat_map(|s| s.intervals().iter().copied())
        .collect();
    all.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut merged: Vec<(f64, f64)> = Vec::with_capacity(all.len());
    for (start, end) in all {
        match merged.last_mut() {
            Some(last) if start <= last.1 => last.1 = last.1.max(end),
            _ => merged.push((start, end)),
        }
    }
    merged
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn schedules_validate_and_answer() {
        let s = Schedule::new(vec![(0.0, 5.0), (10.0, f64::INFINITY)]).unwrap();
        assert!(s.on(0.0) && s.on(4.9) && !s.on(5.0) && !s.on(7.0) && s.on(1e9));
        assert!(Schedule::new(vec![]).is_err());
        assert!(
            Schedule::new(vec![(5.0, 1.0)])
                .unwrap_err()
                .contains("reversed")
        );
        assert!(
            Schedule::new(vec![(0.0, 5.0), (4.0, 6.0)])
                .unwrap_err()
                .contains("overlap")
        );
        assert!(Schedule::new(vec![(f64::NAN, 1.0)]).is_err());
        assert!(Schedule::new(vec![(0.0, f64::NAN)]).is_err());
    }

    #[test]
    fn the_union_merges_and_always_on_lights_cover_everything() {
        let a = Arc::new(Schedule::new(vec![(0.0, 5.0), (20.0, 30.0)]).unwrap());
        let b = Arc::new(Schedule::new(vec![(3.0, 8.0)]).unwrap());
        let timeline = Timeline::new(2, vec![(0, a.clone()), (1, b)], vec![]);
        assert_eq!(timeline.any_on(), &[(0.0, 8.0), (20.0, 30.0)]);
        assert!(timeline.is_timed() && timeline.on(0, 4.0) && !timeline.on(0, 6.0));
        let partly = Timeline::new(2, vec![(0, a)], vec![]);
        assert_eq!(partly.any_on(), &[(f64::NEG_INFINITY, f64::INFINITY)]);
        assert!(partly.on(1, -1e9));
        assert!(!Timeline::default().is_timed());
    }
}
