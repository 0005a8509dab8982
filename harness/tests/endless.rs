//! W127 against the run (the generator is `harness::endless`): a fixed
//! seed, a bounded count; `ENDLESS_CASES=n` runs more, `ENDLESS_SEED=n`
//! from another seed.

use harness::endless::check;
use harness::jit_diff::Choices;
use vm::Status;

#[test]
fn a_loop_w127_warns_about_ends_only_with_an_alarm_once_it_goes_round() {
    let cases: u32 = std::env::var("ENDLESS_CASES").map_or(800, |n| n.parse().unwrap_or(800));
    let seed = std::env::var("ENDLESS_SEED").map_or(0x127, |n| n.parse().unwrap_or(1));
    let mut c = Choices::Seed(seed);
    let (mut warned_round, mut ended_round) = (0, 0);
    for _ in 0..cases {
        let o = check(&mut c);
        assert!(
            o.holds(),
            "W127 was given and the loop went round, yet the run ended with {:?}:\n{}",
            o.end,
            o.src
        );
        warned_round += u32::from(o.warned && o.went_round);
        ended_round += u32::from(!o.warned && o.went_round && o.end == Status::Done);
    }
    // Both kinds were made: warned loops that went round (and ran into
    // the budget), and loops that went round and ended at M30.
    eprintln!("{cases} programs: {warned_round} warned loops went round, {ended_round} loops went round and ended");
    assert!(warned_round >= cases / 20, "{warned_round}");
    assert!(ended_round >= cases / 20, "{ended_round}");
}
