//! The dialect's error codes as the static names diagnostics carry.

const CODES: &[&str] = &[
    "E1001", "E1002", "E1003", "E1004", "E1005", "E1006", "E1007", "E1008", "E1009", "E1010",
    "E1011", "E1012", "E1013", "E1014", "E1015", "E2001", "E2002", "E2003", "E2004", "E2005",
    "E2006", "E2007", "E2010", "E2012", "E2013", "E2014", "E2015", "E2020", "E2021", "E2022",
    "E2040", "E2050", "E2060", "E2061", "E2099", "E4001", "E4002", "E4004", "E4005", "E4006",
    "E4007", "E4008", "E4009", "E4010", "E4011", "E4030", "E4031", "E4032", "E4033", "E4034",
    "E4035", "E4036", "E5001", "E5002", "E5003", "E5004", "E5005", "E5006", "E5007", "E5008",
    "E5009", "E5010", "E5011", "E6001", "E6002", "E6003", "E6004", "E6005", "E6008", "E7001",
    "E7002", "E7003", "E7004", "E7005", "E7006", "E7007", "E7008",
];

/// `E4001` for 4001; an unlisted number maps to `E0000` (never expected).
pub fn name(code: u16) -> &'static str {
    let want = format!("E{code:04}");
    CODES
        .iter()
        .find(|c| **c == want)
        .copied()
        .unwrap_or("E0000")
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
