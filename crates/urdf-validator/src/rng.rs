//! A small, seeded, platform-independent random generator (SplitMix64), so sampled results are the same
//! byte for byte on every machine and every version of this tool.

/// SplitMix64 (Steele, Lea, Flood 2014): 64-bit state, full period, passes BigCrush.
#[derive(Clone, Debug)]
pub struct SplitMix64 {
    state: u64,
}

impl SplitMix64 {
    /// A generator seeded with `seed`.
    pub fn new(seed: u64) -> Self {
        SplitMix64 { state: seed }
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.state = self.state.wrapping_add(GAMMA);
        mix(self.state)
    }

    /// Uniform in `[0, 1)` with 53 random bits.
    pub fn next_f64(&mut self) -> f64 {
        unit(self.next_u64())
    }

    /// Uniform in `[lo, hi)`.
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next_f64()
    }

    /// What the `ahead + 1`-th call of [`SplitMix64::uniform`] from now would return, without drawing:
    /// SplitMix64's state only counts, so any draw can be computed out of order (and several at once).
    #[inline(always)]
    pub fn uniform_ahead(&self, ahead: u64, lo: f64, hi: f64) -> f64 {
        let state = self
            .state
            .wrapping_add(ahead.wrapping_add(1).wrapping_mul(GAMMA));
        lo + (hi - lo) * unit(mix(state))
    }

    /// Skip `draws` draws (as if they had been made).
    pub fn skip(&mut self, draws: u64) {
        self.state = self.state.wrapping_add(draws.wrapping_mul(GAMMA));
    }
}

/// SplitMix64's increment of the state per draw.
const GAMMA: u64 = 0x9E37_79B9_7F4A_7C15;

/// SplitMix64's output function of a state.
#[inline(always)]
fn mix(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// 64 random bits as a uniform number in `[0, 1)` with 53 of them.
#[inline(always)]
fn unit(bits: u64) -> f64 {
    (bits >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reference_sequence_and_range() {
        // First outputs of SplitMix64 seeded with 0 (reference implementation values).
        let mut rng = SplitMix64::new(0);
        assert_eq!(rng.next_u64(), 0xE220_A839_7B1D_CDAF);
        assert_eq!(rng.next_u64(), 0x6E78_9E6A_A1B9_65F4);
        let mut rng = SplitMix64::new(7);
        // Draws computed ahead are the draws made in turn.
        let ahead: Vec<f64> = (0..100).map(|n| rng.uniform_ahead(n, -2.0, 3.0)).collect();
        let drawn: Vec<f64> = (0..100).map(|_| rng.uniform(-2.0, 3.0)).collect();
        assert_eq!(ahead, drawn);
        let mut skipped = SplitMix64::new(7);
        skipped.skip(100);
        assert_eq!(skipped.next_u64(), rng.next_u64());
        assert!((0..1000)
            .map(|_| rng.uniform(-2.0, 3.0))
            .all(|v| (-2.0..3.0).contains(&v)));
    }
}
