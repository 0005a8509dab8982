#[path = "stress.rs"]
#[allow(dead_code)]
mod stress;

#[test]
fn dbg() {
    let r = stress::run_seed(1, &mut |t, s| if (23.0..23.5).contains(&t) { eprintln!("{t:.3} {s}") });
    for k in 23415..23426 { let p = &r.pts[k]; eprintln!("{k} t {:.3} r {:.6} z {:.6} feed {:.3} line {}", p.time_s, p.axis_x/2.0, p.axis_z, p.feed, p.line); }
}
