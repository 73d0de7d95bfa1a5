//! A seeded pseudo-random stream for reproducible "random" test cases.

/// xorshift64* (Vigna 2016): small, deterministic, good enough to pick mutations, flips and
/// samples; the same seed gives the same stream on every platform. The seed must not be 0.
///
/// ```
/// let mut rng = conformap_testkit::XorShift64Star(0x5eed);
/// let k = rng.below(10);
/// assert!(k < 10);
/// ```
#[derive(Debug, Clone)]
pub struct XorShift64Star(pub u64);

impl XorShift64Star {
    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }

    /// A number in `0..n` (0 when `n` is 0).
    pub fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n.max(1) as u64) as usize
    }
}
