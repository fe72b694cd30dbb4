//! Sine and cosine of several angles at once, bit for bit what `libm::sincos` returns.
//!
//! `libm::sincos` (FreeBSD's msun) branches on the size of the angle, which keeps the compiler from
//! evaluating several angles in one vector register. Here the branches of the common cases become
//! selects: |x| ≤ 5π/4 (every joint limit within a turn and a quarter), evaluated with msun's own
//! reduction and kernel polynomials, in the same order of operations, so every result is the same bits.
//! The rare rest (larger angles, angles within 2⁻²⁷ of zero, the few next to π/2 and π whose reduction
//! needs more care, NaN) is handed to `libm::sincos` one by one.
//!
//! msun's branches, as selects: |x| ≤ π/4 (high word ≤ 0x3fe921fb) takes `k_sin(x, 0, 0)` and
//! `k_cos(x, 0)`; |x| ≤ 3π/4 (≤ 0x4002d97c) takes one quarter turn off with `z = x ∓ PIO2_1`,
//! `y0 = z ∓ PIO2_1T`, `y1 = (z − y0) ∓ PIO2_1T`, n = ±1; |x| ≤ 5π/4 (≤ 0x400f6a7a) two, n = ±2; then
//! `k_sin(y0, y1, 1)`, `k_cos(y0, y1)` and the quadrant n & 3.

// msun's kernel coefficients (k_sin.c, k_cos.c) and the first reduction step of e_rem_pio2.c, by their
// bits (as msun gives them).
const S1: f64 = f64::from_bits(0xBFC5_5555_5555_5549);
const S2: f64 = f64::from_bits(0x3F81_1111_1110_F8A6);
const S3: f64 = f64::from_bits(0xBF2A_01A0_19C1_61D5);
const S4: f64 = f64::from_bits(0x3EC7_1DE3_57B1_FE7D);
const S5: f64 = f64::from_bits(0xBE5A_E5E6_8A2B_9CEB);
const S6: f64 = f64::from_bits(0x3DE5_D93A_5ACF_D57C);
const C1: f64 = f64::from_bits(0x3FA5_5555_5555_554C);
const C2: f64 = f64::from_bits(0xBF56_C16C_16C1_5177);
const C3: f64 = f64::from_bits(0x3EFA_01A0_19CB_1590);
const C4: f64 = f64::from_bits(0xBE92_7E4F_809C_52AD);
const C5: f64 = f64::from_bits(0x3E21_EE9E_BDB4_B1C4);
const C6: f64 = f64::from_bits(0xBDA8_FAE9_BE88_38D4);
/// First 33 bits of π/2.
const PIO2_1: f64 = f64::from_bits(0x3FF9_21FB_5440_0000);
/// π/2 − PIO2_1.
const PIO2_1T: f64 = f64::from_bits(0x3DD0_B461_1A62_6331);

// msun's thresholds on the high word of |x|, as the smallest |x| past them: positive doubles order as
// their bits do, so `high word of |x| <= T` is `|x| < above(T)` (false for NaN), a compare the compiler
// can vectorise.
/// Every |x| whose high word is `high` or less is below this.
const fn above(high: u32) -> f64 {
    f64::from_bits(((high as u64) + 1) << 32)
}
/// The high word `high` itself is at least this.
const fn at(high: u32) -> f64 {
    f64::from_bits((high as u64) << 32)
}
/// |x| below this (< 2⁻²⁷·√2): sin x = x, cos x = 1, left to libm, which also raises its flags.
const TINY: f64 = at(0x3e46_a09e);
/// |x| below this (~π/4): no reduction.
const PIO4: f64 = above(0x3fe9_21fb);
/// |x| below this (~3π/4): one quarter turn off.
const THREE_PIO4: f64 = above(0x4002_d97c);
/// |x| below this (~5π/4): two quarter turns off.
const FIVE_PIO4: f64 = above(0x400f_6a7a);
/// msun reduces |x| next to π/2 and π (high words 0x3ff921fb and 0x400921fb) with more care.
const NEAR_PIO2: (f64, f64) = (at(0x3ff9_21fb), above(0x3ff9_21fb));
const NEAR_PI: (f64, f64) = (at(0x4009_21fb), above(0x4009_21fb));

/// `sin x` and `cos x` of every lane into `sin` and `cos`, each the same bits as `libm::sincos(x)`.
/// Written for the compiler to vectorise: fast where the caller is compiled for AVX2, slower than
/// `libm::sincos` lane by lane on plain SSE2 (which has no blend). The results go into the caller's
/// arrays: returned, 64 lanes' worth would be copied out again.
#[inline(always)]
pub fn sincos<const N: usize>(x: &[f64; N], sin: &mut [f64; N], cos: &mut [f64; N]) {
    let mut exact = [0u64; N];
    // Branch-free over the lanes: every condition is a select.
    for k in 0..N {
        let x = x[k];
        let a = x.abs();
        let (reduced, two) = (a >= PIO4, a >= THREE_PIO4);
        // Quarter turns taken off (msun's n: 0, ±1 or ±2, with the sign of x) and the remainder y0 + y1.
        let quarters = if two {
            2.0
        } else if reduced {
            1.0
        } else {
            0.0
        };
        let step = if x < 0.0 { -quarters } else { quarters };
        let z = x - step * PIO2_1;
        let y0 = z - step * PIO2_1T;
        let y1 = (z - y0) - step * PIO2_1T;
        let y0 = if reduced { y0 } else { x };
        let y1 = if reduced { y1 } else { 0.0 };
        // k_sin(y0, y1, iy) and k_cos(y0, y1).
        let z = y0 * y0;
        let w = z * z;
        let r = S2 + z * (S3 + z * S4) + z * w * (S5 + z * S6);
        let v = z * y0;
        let s_reduced = y0 - ((z * (0.5 * y1 - v * r) - y1) - v * S1);
        let s_direct = y0 + v * (S1 + z * r);
        let s = if reduced { s_reduced } else { s_direct };
        let r = z * (C1 + z * (C2 + z * C3)) + w * w * (C4 + z * (C5 + z * C6));
        let hz = 0.5 * z;
        let w = 1.0 - hz;
        let c = w + (((1.0 - w) - hz) + (z * r - y0 * y1));
        // The quadrant n & 3: 0 (s, c), 1 (c, −s), 2 (−s, −c), 3 (−c, s).
        let odd = reduced && a < THREE_PIO4;
        let (s, c) = (if odd { c } else { s }, if odd { s } else { c });
        let negate_sin = two || (odd && x < 0.0);
        let negate_cos = two || (odd && x >= 0.0);
        sin[k] = if negate_sin { -s } else { s };
        cos[k] = if negate_cos { -c } else { c };
        let apart = |(lo, hi): (f64, f64)| a < lo || a >= hi;
        let covered = (TINY..FIVE_PIO4).contains(&a) && apart(NEAR_PIO2) && apart(NEAR_PI);
        exact[k] = u64::from(covered);
    }
    if exact.iter().sum::<u64>() != N as u64 {
        for k in 0..N {
            if exact[k] == 0 {
                (sin[k], cos[k]) = libm::sincos(x[k]);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::SplitMix64;

    /// Every lane, against libm bit for bit: uniform angles over ±4 (every branch, and the fallback),
    /// the thresholds' neighbours, the angles next to π/2 and π, zeros, tiny angles, NaN and infinities.
    #[test]
    fn same_bits_as_libm() {
        let mut angles: Vec<f64> = Vec::new();
        let mut rng = SplitMix64::new(5);
        angles.extend((0..200_000).map(|_| rng.uniform(-4.0, 4.0)));
        for high in [
            0x3e46_a09e,
            0x3fe9_21fb,
            0x4002_d97c,
            0x400f_6a7a,
            0x3ff9_21fb,
            0x4009_21fb,
        ] {
            for delta in [-1i64, 0, 1] {
                let bits = ((i64::from(high) + delta) as u64) << 32;
                for low in [0u64, 1, 0x5444_2d18, 0xffff_ffff] {
                    let a = f64::from_bits(bits | low);
                    angles.extend([a, -a]);
                }
            }
        }
        let pi = std::f64::consts::PI;
        for a in [
            0.0,
            -0.0,
            1e-300,
            1e-9,
            pi / 4.0,
            pi / 2.0,
            pi,
            1.25 * pi,
            100.0,
        ] {
            angles.extend([a, -a, f64::from_bits(a.to_bits() + 1)]);
        }
        angles.extend([f64::NAN, f64::INFINITY, f64::NEG_INFINITY]);
        for lanes in angles.chunks(8) {
            let mut x = [0.3; 8];
            x[..lanes.len()].copy_from_slice(lanes);
            let (mut s, mut c) = ([0.0; 8], [0.0; 8]);
            sincos(&x, &mut s, &mut c);
            for k in 0..8 {
                let (es, ec) = libm::sincos(x[k]);
                assert_eq!(
                    (s[k].to_bits(), c[k].to_bits()),
                    (es.to_bits(), ec.to_bits()),
                    "sincos({:e}) = ({}, {}), libm: ({}, {})",
                    x[k],
                    s[k],
                    c[k],
                    es,
                    ec
                );
            }
        }
    }
}
