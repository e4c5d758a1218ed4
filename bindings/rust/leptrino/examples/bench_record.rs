//! Per-sample CPU cost of `Sensor::record()` and of the sample iterator, the
//! Rust counterpart of bindings/python/bench_record.py (same method).
//!
//! The virtual sensor runs on a C thread of this process (`Sensor::open_sim`),
//! so the figures are the CPU time of the calling thread only
//! (CLOCK_THREAD_CPUTIME_ID): the C session's reads and the Rust around them.
//! Prints the median of the runs for each; asserts nothing.
//!
//!     cargo run --release --example bench_record -- [--runs 5] [--seconds 2] [--latency-ms 50]

use std::time::{Duration, Instant};

use leptrino::{sys, Options, Sensor, SimOptions};

fn thread_cpu() -> f64 {
    let mut ts = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: valid out pointer.
    unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut ts) };
    ts.tv_sec as f64 + ts.tv_nsec as f64 * 1e-9
}

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(|a, b| a.partial_cmp(b).unwrap());
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        (v[n / 2 - 1] + v[n / 2]) / 2.0
    }
}

/// CPU per sample of lep_session_read alone, in a session of its own
/// (opened through leptrino-sys, options by name) with this latency budget;
/// one value per run.
fn session_alone(latency_ms: u64, runs: usize, seconds: f64) -> Vec<f64> {
    let cap = (1200.0 * seconds * 1.2) as usize + 1000;
    let (mut t, mut tu, mut st, mut fl, mut sq) = (
        vec![0.0; cap],
        vec![0.0; cap],
        vec![0u8; cap],
        vec![0u8; cap],
        vec![0u16; cap],
    );
    let (mut raw, mut zeroed, mut si) =
        (vec![0i16; cap * 6], vec![0.0; cap * 6], vec![0.0; cap * 6]);
    let mut session = std::ptr::null_mut();
    // SAFETY: plain C calls with valid pointers and NUL-terminated names; the
    // options handle is copied by lep_session_open and freed after.
    unsafe {
        let o = sys::lep_options_new();
        assert!(!o.is_null());
        let null = std::ptr::null_mut();
        assert_eq!(sys::lep_options_set_int(o, c"sim".as_ptr(), 1, null, 0), 0);
        assert_eq!(
            sys::lep_options_set_int(o, c"latency".as_ptr(), latency_ms as i64, null, 0),
            0
        );
        assert_eq!(sys::lep_session_open(o, &mut session, null, 0), 0);
        sys::lep_options_free(o);
    }
    let mut out = Vec::new();
    for _ in 0..runs {
        // SAFETY: the session is open.
        unsafe { assert_eq!(sys::lep_session_start(session), 0) };
        let end = Instant::now() + Duration::from_secs_f64(seconds);
        let c0 = thread_cpu();
        let mut total = 0usize;
        while Instant::now() < end && total < cap {
            let mut n = 0usize;
            // SAFETY: every column holds cap rows from row `total` on: cap - total.
            unsafe {
                sys::lep_session_read(
                    session,
                    250,
                    cap - total,
                    &mut n,
                    t.as_mut_ptr().add(total),
                    tu.as_mut_ptr().add(total),
                    si.as_mut_ptr().add(total * 6),
                    raw.as_mut_ptr().add(total * 6),
                    zeroed.as_mut_ptr().add(total * 6),
                    st.as_mut_ptr().add(total),
                    fl.as_mut_ptr().add(total),
                    sq.as_mut_ptr().add(total),
                )
            };
            total += n;
        }
        let c1 = thread_cpu();
        unsafe { sys::lep_session_stop(session) };
        out.push((c1 - c0) / total.max(1) as f64 * 1e6);
    }
    unsafe { sys::lep_session_close(session) };
    out
}

fn main() -> leptrino::Result<()> {
    let mut runs = 5usize;
    let mut seconds = 2.0f64;
    let mut latency_ms = 50u64;
    let args: Vec<String> = std::env::args().skip(1).collect();
    for pair in args.chunks(2) {
        let v = pair.get(1).map(String::as_str).unwrap_or("");
        match pair[0].as_str() {
            "--runs" => runs = v.parse().expect("--runs N"),
            "--seconds" => seconds = v.parse().expect("--seconds S"),
            "--latency-ms" => latency_ms = v.parse().expect("--latency-ms MS"),
            other => panic!("unknown argument {other}"),
        }
    }
    let options = Options::new().latency(Duration::from_millis(latency_ms));
    let mut s = Sensor::open_sim(&SimOptions::new(), &options)?;
    s.record_count(100)?; // warm up (allocations, first batch)

    // record() in a running stream (as a long recording amortises start and stop)
    s.start()?;
    let (mut rec_us, mut lost, mut n_rec) = (Vec::new(), 0, Vec::new());
    for _ in 0..runs {
        let c0 = thread_cpu();
        let rec = s.record(Duration::from_secs_f64(seconds))?;
        let c1 = thread_cpu();
        rec_us.push((c1 - c0) / rec.len() as f64 * 1e6);
        n_rec.push(rec.len() as f64);
        lost += rec.missing();
    }
    s.stop()?;

    drop(s);
    // The session alone (the C figure): lep_session_read into one big batch,
    // nothing around it but the loop; at the sensor's budget, and at the
    // 100 ms that record() sets while it runs.
    let mut c_us = session_alone(latency_ms, runs, seconds);
    let mut c100_us = session_alone(100, runs, seconds);

    // iterating, sample by sample
    let mut s = Sensor::open_sim(&SimOptions::new(), &options)?;
    let mut it_us = Vec::new();
    for _ in 0..runs {
        let c0 = thread_cpu();
        let mut n = 0usize;
        let mut t0 = None;
        for x in s.stream()? {
            let x = x?;
            if x.t - *t0.get_or_insert(x.t) >= seconds {
                break;
            }
            n += 1;
        }
        let c1 = thread_cpu();
        it_us.push((c1 - c0) / n as f64 * 1e6);
    }

    let fmt = |v: &[f64]| {
        v.iter()
            .map(|x| format!("{x:.2}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let (r_runs, i_runs) = (fmt(&rec_us), fmt(&it_us));
    let (rec_m, it_m, c_m) = (median(&mut rec_us), median(&mut it_us), median(&mut c_us));
    let c100_m = median(&mut c100_us);
    println!(
        "rust, virtual sensor at 1200 Hz, latency budget {latency_ms} ms, {runs} runs of {seconds} s \
         ({} samples each, {lost} lost)",
        median(&mut n_rec)
    );
    println!("record():   median {rec_m:.2} us CPU per sample (runs: {r_runs})");
    println!(
        "(the session's reads alone: median {c_m:.2} us CPU per sample at {latency_ms} ms, \
         {c100_m:.2} us at record()'s 100 ms; Rust adds {:.2} us to record())",
        rec_m - c100_m
    );
    println!("iterating:  median {it_m:.2} us CPU per sample (runs: {i_runs})");
    Ok(())
}
