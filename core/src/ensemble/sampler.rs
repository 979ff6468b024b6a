//! Each member's own random stream, a function of the ensemble's seed and the member's index
//! only.
//!
//! The rule, enough to reproduce member `i` alone with any ChaCha implementation: the
//! generator is ChaCha with 8 rounds ([`ChaCha8Rng`] of the `chacha20` crate, re-exported by
//! `rand`), keyed by `SeedableRng::seed_from_u64(seed)` (rand_core's PCG32 expansion of the
//! 64-bit seed into the 32-byte key), on stream (nonce) `i`, from word position 0. Streams of
//! different members never overlap (each has 2⁶⁸ words), so no member's draws depend on how
//! many numbers another member drew, on the thread that ran it or on the order of completion.

use rand::rngs::ChaCha8Rng;
use rand::SeedableRng;

/// The random generator a member's sampler draws from.
pub type MemberRng = ChaCha8Rng;

/// The random stream of member `index` of the ensemble with `seed` (see the module
/// documentation for the exact rule).
///
/// ```
/// use varmass_core::ensemble::member_rng;
/// use varmass_core::ensemble::rand::RngExt;
///
/// let first: f64 = member_rng(7, 12).random();
/// let again: f64 = member_rng(7, 12).random();
/// let other: f64 = member_rng(7, 13).random();
/// assert_eq!(first.to_bits(), again.to_bits());
/// assert_ne!(first.to_bits(), other.to_bits());
/// ```
pub fn member_rng(seed: u64, index: u64) -> MemberRng {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(index);
    rng
}
