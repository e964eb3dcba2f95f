//! Smoke test of the KR benchmark's code paths (`benches/kr.rs`): every case runs a few times on
//! both engines and the table is printed. No timings are asserted.

#[path = "../benches/kr.rs"]
#[allow(dead_code)]
mod bench;

#[test]
fn benchmark_runs_in_quick_mode() {
    std::env::set_var("KR_BENCH_QUICK", "1");
    bench::main();
    assert!(
        bench::rss_bytes() > 0,
        "RSS should be readable from /proc/self/statm"
    );
}
