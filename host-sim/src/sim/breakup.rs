//! Break-ups: fragments released from a parent object at a time, which the prior does not know.

use super::error::SsaError;
use super::ssa::PASS_GAP;
use super::truth::{ObjectTruth, Track, track};
use super::vector::{add, norm, scale, vel};
use crate::sim::orbit::Propagator;
use crate::sim::rng::{Random, Stream};

/// A break-up of `parent` into `count` new fragments (stream [`Stream::Scenario`] 3,000,000): at a time
/// 2 to 15 minutes before the start of one of the parent's passes after the first 5 minutes of the run,
/// each fragment takes the parent's state and a velocity kick of 2 to 30 m/s in a uniformly random
/// direction. The parent continues on its orbit. Returns the fragments (born then, unknown to the prior),
/// each with its truth at `schedule`'s times.
pub(crate) fn breakup(
    seed: u64,
    parent: &ObjectTruth,
    count: usize,
    group: usize,
    schedule: &[(f64, usize)],
    visible: &[bool],
    sensors: usize,
) -> Result<Vec<(ObjectTruth, Track)>, SsaError> {
    let mut random = Random::stream(seed, Stream::Scenario, 3_000_000);
    let mut starts = vec![];
    let mut last = vec![f64::NEG_INFINITY; sensors];
    for (k, (&(t, s), &v)) in schedule.iter().zip(visible).enumerate() {
        if v {
            if t - last[s] > PASS_GAP && t >= 300.0 {
                starts.push(k);
            }
            last[s] = t;
        }
    }
    let Some(&last_start) = starts.last() else { return Err(SsaError::OrbitSearch) };
    let start = starts[((random.uniform() * starts.len() as f64) as usize).min(starts.len() - 1)];
    let start = if schedule[start].0 < 300.0 { last_start } else { start };
    let time = (schedule[start].0 - random.between(120.0, 900.0)).max(1.0);
    let at_breakup = Propagator::EARTH.propagate(parent.initial_state, time)?;
    let times: Vec<f64> = schedule.iter().map(|&(t, _)| t).collect();
    let mut fragments = Vec::with_capacity(count);
    for _ in 0..count {
        let direction = [random.normal(), random.normal(), random.normal()];
        let speed = random.between(0.002, 0.030);
        let kick = scale(direction, speed / norm(direction).max(f64::MIN_POSITIVE));
        let v = add(vel(&at_breakup), kick);
        let state = [at_breakup[0], at_breakup[1], at_breakup[2], v[0], v[1], v[2]];
        let initial = Propagator::EARTH.propagate(state, -time)?;
        let fragment =
            ObjectTruth { initial_state: initial, group: Some(group), in_prior: false, birth_time: Some(time) };
        fragments.push((fragment, track(initial, &times)?));
    }
    Ok(fragments)
}
