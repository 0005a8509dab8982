//! The dialect's error codes as the static names diagnostics carry; the
//! table itself is the kernel's `nc::error::Alarm`.

use nc::error::Alarm;

/// `E4001` for 4001; an unlisted number maps to `E0000` (never expected).
pub fn name(code: u16) -> &'static str {
    Alarm::from_code(code).map_or("E0000", Alarm::name)
}

#[cfg(test)]
mod tests {
    #[test]
    fn every_code_maps_to_its_name() {
        assert_eq!(super::name(4001), "E4001");
        assert_eq!(super::name(1009), "E1009");
        assert_eq!(super::name(9999), "E0000");
    }
}
