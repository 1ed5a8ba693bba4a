//! Where the low-speed asymptote (Eqs. 18/19) may stand in for the full
//! friction integral.
//!
//! The asymptote's relative error grows with speed from zero (the next
//! term is smaller by a factor of order (vτ_max/a0)^p), so the speeds it
//! may serve form an initial run of an increasing sweep. It is found by
//! probing the full model: at the slowest speed, then a decade at a time
//! upwards until a probe misses, then by bisection between the last hit
//! and the miss. Cost: one μ per probed decade plus about log2 of the
//! speeds in the last decade. A run that turns bad between two decade
//! probes and good again would be missed; for the monotone deviation of a
//! solid with a longest relaxation time this does not happen.

use crate::error::ModelError;
use crate::modulus::ViscoelasticModulus;
use crate::scene::Scene;

/// The number of leading speeds of `speeds` (increasing, m/s) at which the
/// asymptote is within `budget` (relative) of `scene`'s μ, and the largest
/// relative deviation seen at the accepted probes.
pub(super) fn asymptote_run<M: ViscoelasticModulus>(
    scene: &Scene<M>,
    speeds: &[f64],
    budget: f64,
) -> Result<(usize, f64), ModelError> {
    let n = speeds.len();
    let deviation = |i: usize| -> Result<f64, ModelError> {
        let v = speeds[i];
        Ok((scene.low_speed_asymptote(v) / scene.friction(v)? - 1.0).abs())
    };
    if n == 0 {
        return Ok((0, 0.0));
    }
    let first = deviation(0)?;
    if first.is_nan() || first > budget {
        return Ok((0, 0.0));
    }
    let mut seen = first;
    let mut hit = 0;
    let miss = loop {
        if hit == n - 1 {
            return Ok((n, seen));
        }
        let target = 10.0 * speeds[hit];
        let next = (hit + 1..n).find(|&i| speeds[i] >= target).unwrap_or(n - 1);
        let d = deviation(next)?;
        if d <= budget {
            seen = seen.max(d);
            hit = next;
        } else {
            break next;
        }
    };
    let mut miss = miss;
    while miss - hit > 1 {
        let mid = (hit + miss) / 2;
        let d = deviation(mid)?;
        if d <= budget {
            seen = seen.max(d);
            hit = mid;
        } else {
            miss = mid;
        }
    }
    Ok((hit + 1, seen))
}
