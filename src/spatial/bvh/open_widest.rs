//! The widest node opener the processor offers, chosen once per call: work
//! generic over [`NodeLanes`] is compiled inside one entry point per
//! instruction set, so that the opener is inlined into it, and run through
//! the one the processor has.

use super::open::NodeLanes;
#[cfg(target_arch = "x86_64")]
use super::open_avx2::Avx2;
#[cfg(target_arch = "x86_64")]
use super::open_avx512::Avx512;
use super::open_portable::Portable;

/// Work generic over how nodes are opened (a ray walk, a stream of walks).
pub(crate) trait LanesJob {
    /// What the work answers.
    type Output;
    /// Does the work with nodes opened by `lanes`. Implementations should be
    /// `#[inline(always)]`, so that the work is compiled inside each entry
    /// point of [`with_widest_lanes`] with that entry point's instruction set.
    fn run(self, lanes: impl NodeLanes) -> Self::Output;
}

/// Runs `job` with AVX-512 or AVX2 node openers where the processor has
/// them, else with the portable one; the answer is the same either way.
#[inline(always)]
pub(crate) fn with_widest_lanes<J: LanesJob>(job: J) -> J::Output {
    #[cfg(target_arch = "x86_64")]
    if let Some(avx2) = Avx2::detect() {
        return match avx2.avx512() {
            // SAFETY: the AVX-512 features were detected.
            Some(avx512) => unsafe { run_avx512(job, avx512) },
            // SAFETY: AVX2 was detected.
            None => unsafe { run_avx2(job, avx2) },
        };
    }
    job.run(Portable)
}

/// `job` compiled for AVX-512, with its node opener.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,popcnt,fma,bmi1,bmi2,lzcnt,avx512f,avx512vl,avx512bw,avx512dq")]
fn run_avx512<J: LanesJob>(job: J, lanes: Avx512) -> J::Output {
    job.run(lanes)
}

/// `job` compiled for AVX2, with its node opener.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,popcnt")]
fn run_avx2<J: LanesJob>(job: J, lanes: Avx2) -> J::Output {
    job.run(lanes)
}
