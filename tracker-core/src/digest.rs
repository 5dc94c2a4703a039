//! A 64-bit FNV-1a hash: the tracker's state digest, by which the host and an embedded target are shown to
//! agree bit for bit, and the key that finds identical children quickly.

/// 64-bit FNV-1a over bytes.
///
/// # Examples
/// ```
/// use tracker_core::digest::Fnv1a;
/// let mut hash = Fnv1a::new();
/// hash.write(b"a");
/// assert_eq!(hash.finish(), 0xaf63_dc4c_8601_ec8c); // the published FNV-1a 64 of "a"
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Fnv1a(u64);

impl Default for Fnv1a {
    fn default() -> Self {
        Self::new()
    }
}

impl Fnv1a {
    /// The hash of no byte (the FNV-1a 64 offset basis).
    ///
    /// # Examples
    /// ```
    /// assert_eq!(tracker_core::digest::Fnv1a::new().finish(), 0xcbf2_9ce4_8422_2325);
    /// ```
    pub const fn new() -> Self {
        Fnv1a(0xcbf2_9ce4_8422_2325)
    }

    /// Adds `bytes`.
    ///
    /// # Examples
    /// ```
    /// use tracker_core::digest::Fnv1a;
    /// let (mut whole, mut parts) = (Fnv1a::new(), Fnv1a::new());
    /// whole.write(b"foobar");
    /// parts.write(b"foo");
    /// parts.write(b"bar");
    /// assert_eq!(whole.finish(), parts.finish()); // a stream of bytes, however it is cut
    /// assert_eq!(whole.finish(), 0x8594_4171_f739_67e8); // the published FNV-1a 64 of "foobar"
    /// ```
    pub fn write(&mut self, bytes: &[u8]) {
        for &byte in bytes {
            self.0 ^= u64::from(byte);
            self.0 = self.0.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }

    /// Adds a `u64` as 8 little-endian bytes.
    ///
    /// # Examples
    /// ```
    /// use tracker_core::digest::Fnv1a;
    /// let (mut a, mut b) = (Fnv1a::new(), Fnv1a::new());
    /// a.write_u64(1.5f64.to_bits());
    /// b.write(&1.5f64.to_bits().to_le_bytes());
    /// assert_eq!(a.finish(), b.finish());
    /// ```
    pub fn write_u64(&mut self, value: u64) {
        self.write(&value.to_le_bytes());
    }

    /// The hash of everything written.
    ///
    /// # Examples
    /// ```
    /// use tracker_core::digest::Fnv1a;
    /// let mut hash = Fnv1a::new();
    /// hash.write(b"a");
    /// let first = hash.finish();
    /// hash.write(b"b");
    /// assert_ne!(hash.finish(), first); // finishing does not reset the hash
    /// ```
    pub fn finish(&self) -> u64 {
        self.0
    }
}
