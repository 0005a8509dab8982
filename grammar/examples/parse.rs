//! Parses files (or standard input) and prints the diagnostics, or the
//! syntax tree with `--ast`: `cargo run -p grammar --example parse -- FILE…`

use std::io::Read;

fn main() {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    let show_ast = args.iter().any(|a| a == "--ast");
    args.retain(|a| a != "--ast");
    let inputs: Vec<(String, Vec<u8>)> = if args.is_empty() {
        let mut buf = Vec::new();
        if let Err(e) = std::io::stdin().read_to_end(&mut buf) {
            eprintln!("stdin: {e}");
            std::process::exit(2);
        }
        vec![("<stdin>".to_string(), buf)]
    } else {
        args.iter()
            .map(|p| match std::fs::read(p) {
                Ok(b) => (p.clone(), b),
                Err(e) => {
                    eprintln!("{p}: {e}");
                    std::process::exit(2);
                }
            })
            .collect()
    };
    let mut failed = false;
    for (name, bytes) in inputs {
        let (ast, diags) = grammar::parse(&bytes);
        if show_ast {
            println!("{ast:#?}");
        }
        let file = grammar::SourceFile::new(name, bytes.as_slice());
        for d in &diags {
            failed |= d.is_error();
            println!("{}", file.render(d));
        }
    }
    std::process::exit(i32::from(failed));
}
