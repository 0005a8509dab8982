//! What `gbvm run --plot` learns from the program's source text, when the
//! file the module was compiled from can still be read: the program's name
//! (the comment of its `O` line), the stock of a `[BILLET` simulator line
//! (which the compiler ignores with W102) and the lines of its roughing
//! cycles (G71/G72/G73), whose start point is the corner of the stock.

use runtime::plot::Stock;

/// The facts, all optional.
#[derive(Debug, Default, PartialEq)]
pub struct ProgramInfo {
    /// `O0201` and the comment on its line.
    pub number: Option<u32>,
    pub name: Option<String>,
    pub billet: Option<Stock>,
    /// 1-based lines of the main file holding G71, G72 or G73.
    pub roughing: Vec<u32>,
}

impl ProgramInfo {
    pub fn read(src: &str) -> ProgramInfo {
        let mut info = ProgramInfo::default();
        for (i, raw) in src.lines().enumerate() {
            let line = raw.trim();
            if let Some(rest) = line.strip_prefix(['[']) {
                if let Some(words) = strip_prefix_ignore_case(rest, "BILLET") {
                    info.billet = info.billet.or_else(|| parse_stock(words).ok());
                }
                continue;
            }
            let code = uncommented(line).to_ascii_uppercase();
            if info.number.is_none() {
                if let Some((n, name)) = o_line(line) {
                    info.number = Some(n);
                    info.name = name;
                }
            }
            if has_roughing_code(&code) {
                info.roughing.push(i as u32 + 1);
            }
        }
        info
    }

    /// The plot's title: the file, the O number and the program's name.
    pub fn title(&self, file: &str, number: Option<u32>) -> String {
        let mut t = file.to_string();
        if let Some(n) = self.number.or(number) {
            t.push_str(&format!("  O{n:04}"));
        }
        if let Some(name) = &self.name {
            t.push_str(&format!(" ({name})"));
        }
        t
    }
}

fn strip_prefix_ignore_case<'a>(s: &'a str, word: &str) -> Option<&'a str> {
    let head = s.get(..word.len())?;
    head.eq_ignore_ascii_case(word).then(|| &s[word.len()..])
}

/// The stock as `--stock` and `[BILLET` write it: `X`diameter `Z`length,
/// in either order, blanks optional (`X55 Z128`, `x55z128`). The bar's face
/// is at Z0.
pub fn parse_stock(words: &str) -> Result<Stock, String> {
    let mut x = None;
    let mut z = None;
    let text: String = words.chars().filter(|c| !c.is_whitespace()).collect();
    let mut rest = text.as_str();
    while let Some(letter) = rest.chars().next() {
        let body = &rest[letter.len_utf8()..];
        let end = body
            .find(|c: char| !(c.is_ascii_digit() || c == '.' || c == '-' || c == '+'))
            .unwrap_or(body.len());
        let value: f64 = body[..end]
            .parse()
            .map_err(|_| format!("stock '{words}': '{letter}' needs a number"))?;
        match letter.to_ascii_uppercase() {
            'X' => x = Some(value),
            'Z' => z = Some(value),
            _ => {}
        }
        rest = &body[end..];
    }
    match (x, z) {
        (Some(d), Some(l)) if d > 0.0 && l > 0.0 && d.is_finite() && l.is_finite() => {
            Ok(Stock::bar(d, l))
        }
        _ => Err(format!(
            "stock '{words}': expected X<diameter> Z<length>, both positive (e.g. X55 Z128)"
        )),
    }
}

/// The text of a line with its `( … )` comments removed.
fn uncommented(line: &str) -> String {
    let mut out = String::new();
    let mut depth = 0;
    for c in line.chars() {
        match c {
            '(' => depth += 1,
            ')' if depth > 0 => depth -= 1,
            _ if depth == 0 => out.push(c),
            _ => {}
        }
    }
    out
}

/// `O1234 (NAME)` or `:1234`: the number and the comment.
fn o_line(line: &str) -> Option<(u32, Option<String>)> {
    let rest = line.strip_prefix(['O', 'o', ':'])?.trim_start_matches(' ');
    let end = rest
        .find(|c: char| !c.is_ascii_digit())
        .unwrap_or(rest.len());
    let n = rest[..end].parse().ok()?;
    let name = rest[end..].split_once('(').and_then(|(_, c)| {
        let c = c.split(')').next().unwrap_or("").trim();
        (!c.is_empty()).then(|| c.to_string())
    });
    Some((n, name))
}

/// G71, G72 or G73 as a word of the (uppercased, uncommented) line, not
/// the start of G710 or G71.5.
fn has_roughing_code(code: &str) -> bool {
    let b = code.as_bytes();
    code.match_indices('G').any(|(i, _)| {
        let digits = &b[i + 1..];
        let word = digits
            .iter()
            .take_while(|c| c.is_ascii_digit() || **c == b'.')
            .count();
        matches!(
            &digits[..word],
            b"71" | b"72" | b"73" | b"071" | b"072" | b"073"
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_the_o_line_the_billet_and_the_roughing_cycles() {
        let src = "%\n[BILLET X58.1 Z46\nO0201(COOLANT NECK) \nG00 X60 Z2\nG71 U2 R1 (ROUGH)\nG71 P10 Q20 U.5 W.1 F.2\nG710\nG70 P10 Q20\n(G73 IN A COMMENT)\nM30\n";
        let info = ProgramInfo::read(src);
        assert_eq!(info.number, Some(201));
        assert_eq!(info.name.as_deref(), Some("COOLANT NECK"));
        assert_eq!(info.billet, Some(Stock::bar(58.1, 46.0)));
        assert_eq!(info.roughing, [5, 6]);
        assert_eq!(info.title("part.nc", None), "part.nc  O0201 (COOLANT NECK)");
    }

    #[test]
    fn stock_words_in_any_order_and_bad_ones_refused() {
        assert_eq!(parse_stock("Z128 X55"), Ok(Stock::bar(55.0, 128.0)));
        assert_eq!(parse_stock("x55z128"), Ok(Stock::bar(55.0, 128.0)));
        assert!(parse_stock("X55").is_err());
        assert!(parse_stock("X-5 Z10").is_err());
        assert!(parse_stock("Xabc Z10").is_err());
        assert!(parse_stock("").is_err());
    }

    #[test]
    fn without_an_o_line_the_module_number_is_used() {
        let info = ProgramInfo::read("G00 X1\n");
        assert_eq!(info.title("p.nc", Some(7)), "p.nc  O0007");
        assert_eq!(info.title("p.nc", None), "p.nc");
    }
}
