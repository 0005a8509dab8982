//! `gbcc -MD`/`-MF`: a make rule naming what a build read, so that `make`
//! rebuilds a `.gbc` when a library program it calls (`-I`) or the machine
//! file changes, as gcc's `-MD` does for headers.

/// Escapes a file name for make: spaces and `#` with a backslash, `$`
/// doubled.
fn escape(name: &str) -> String {
    let mut out = String::new();
    for c in name.chars() {
        match c {
            ' ' | '#' => {
                out.push('\\');
                out.push(c);
            }
            '$' => out.push_str("$$"),
            c => out.push(c),
        }
    }
    out
}

/// `target: dep dep …` on one line, each dependency once, in order.
pub fn rule(target: &str, deps: &[String]) -> String {
    let mut seen: Vec<&str> = Vec::new();
    let mut out = format!("{}:", escape(target));
    for d in deps {
        if !seen.contains(&d.as_str()) {
            seen.push(d);
            out.push(' ');
            out.push_str(&escape(d));
        }
    }
    out.push('\n');
    out
}

#[cfg(test)]
mod tests {
    #[test]
    fn names_are_escaped_and_listed_once() {
        let deps = ["a b.nc".to_string(), "lib/O1$.nc".into(), "a b.nc".into()];
        assert_eq!(
            super::rule("out#1.gbc", &deps),
            "out\\#1.gbc: a\\ b.nc lib/O1$$.nc\n"
        );
    }
}
