//! Basin stability by random sampling: a small seeded generator
//! ([`SplitMix64`], Steele, Lea & Flood 2014) that makes the `k`-th start
//! of a seed the same on every machine, thread count and resume, and the
//! Wilson score interval of a fraction ([`wilson`]).

/// SplitMix64: a 64-bit state advanced by the golden-ratio increment and
/// scrambled by two xor-shift-multiplies. Not for cryptography; its
/// outputs pass BigCrush, which is plenty for uniform starts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SplitMix64 {
    state: u64,
}

impl SplitMix64 {
    /// The generator seeded with `seed`.
    pub fn new(seed: u64) -> Self {
        Self { state: seed }
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.state = self.state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// A uniform number in `[0, 1)`: the top 53 bits.
    pub fn next_unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }
}

/// The `k`-th random start of `seed` in the box `[x0, x1] × [v0, v1]`:
/// its own generator (seeded by `seed` and `k`), so that any start can be
/// computed alone, in any order.
pub fn random_start(seed: u64, k: u64, x: (f64, f64), v: (f64, f64)) -> (f64, f64) {
    let mut g = SplitMix64::new(seed ^ k.wrapping_mul(0xD1B5_4A32_D192_ED03));
    // Discard one output so that neighbouring k do not share a first draw's structure.
    g.next_u64();
    let (a, b) = (g.next_unit(), g.next_unit());
    (x.0 + (x.1 - x.0) * a, v.0 + (v.1 - v.0) * b)
}

/// The 97.5 % quantile of the standard normal distribution.
pub const Z95: f64 = 1.959_963_984_540_054;

/// The Wilson score interval `[lo, hi]` of a fraction `hits / n` at the
/// normal quantile `z` (`[0, 1]` for `n = 0`). Unlike the normal
/// approximation it stays inside `[0, 1]` and is not empty at 0 or `n` hits.
pub fn wilson(hits: usize, n: usize, z: f64) -> [f64; 2] {
    if n == 0 {
        return [0.0, 1.0];
    }
    let n = n as f64;
    let p = hits as f64 / n;
    let z2 = z * z;
    let centre = (p + z2 / (2.0 * n)) / (1.0 + z2 / n);
    let half = z / (1.0 + z2 / n) * (p * (1.0 - p) / n + z2 / (4.0 * n * n)).sqrt();
    [(centre - half).max(0.0), (centre + half).min(1.0)]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn splitmix_matches_the_reference_sequence() {
        // The first outputs of the reference implementation (Vigna's
        // splitmix64.c) seeded with 1234567.
        let mut g = SplitMix64::new(1_234_567);
        let expected = [
            6_457_827_717_110_365_317u64,
            3_203_168_211_198_807_973,
            9_817_491_932_198_370_423,
        ];
        for e in expected {
            assert_eq!(g.next_u64(), e);
        }
    }

    #[test]
    fn units_are_uniform_in_the_unit_interval() {
        let mut g = SplitMix64::new(7);
        let n = 100_000;
        let mut sum = 0.0;
        for _ in 0..n {
            let u = g.next_unit();
            assert!((0.0..1.0).contains(&u));
            sum += u;
        }
        // Mean 1/2, standard error sqrt(1/12/n) ≈ 9e-4.
        assert!((sum / n as f64 - 0.5).abs() < 5e-3);
    }

    #[test]
    fn wilson_against_the_closed_form() {
        // 0 of 10 at z: [0, z² / (n + z²)].
        let [lo, hi] = wilson(0, 10, Z95);
        assert_eq!(lo, 0.0);
        assert!((hi - Z95 * Z95 / (10.0 + Z95 * Z95)).abs() < 1e-15);
        // n/2 hits: centred on 1/2 with half-width z / (2 sqrt(n + z²)),
        // within 2e-5 of the normal interval's z sqrt(1/4n) at n = 10⁴.
        let [lo, hi] = wilson(5000, 10_000, Z95);
        assert!((lo + hi - 1.0).abs() < 1e-12);
        let half = Z95 / (2.0 * (10_000.0 + Z95 * Z95).sqrt());
        assert!((hi - 0.5 - half).abs() < 1e-14);
        assert!((hi - 0.5 - Z95 * 0.005).abs() < 2e-5);
    }
}
