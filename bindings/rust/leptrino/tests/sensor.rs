//! The safe API against the in-process virtual sensor, through a real pty:
//! identity, rated values, recording without loss, tare, faults, a pulled
//! cable, reconnects, errors. The scenarios of the Python suite
//! (bindings/python/tests/test_sensor.py, test_session.py).

use std::time::{Duration, Instant};

use leptrino::{
    sys, Control, Error, ErrorKind, EventKind, Options, Recording, Sensor, SimOptions, Simulator,
};

fn sim_options(pairs: &[(&str, &str)]) -> SimOptions {
    let mut o = SimOptions::new();
    for (k, v) in pairs {
        o.set(k, v).unwrap();
    }
    o
}

fn open_sim(pairs: &[(&str, &str)], options: Options) -> Sensor {
    Sensor::open_sim(&sim_options(pairs), &options).unwrap()
}

fn steps_all_one(rec: &Recording) -> bool {
    rec.seq.windows(2).all(|w| w[1] == w[0].wrapping_add(1))
}

#[test]
fn identity_of_every_model() {
    let models = Simulator::models();
    for m in [
        "CFS018CA201U",
        "CFS034CA301U",
        "PFS055YA501U6",
        "PFS080YS102U6",
    ] {
        assert!(models.iter().any(|x| x == m), "{m} missing from {models:?}");
    }
    for model in &models {
        let o = sim_options(&[
            ("model", model),
            ("serial", "12345678"),
            ("firmware", "1.31"),
            ("output-rate-field", "true"),
        ]);
        let sim = Simulator::start_with(&o).unwrap();
        let s = Sensor::open(sim.port()).unwrap();
        let info = s.product_info();
        assert_eq!(
            (
                info.model.as_str(),
                info.serial.as_str(),
                info.firmware.as_str()
            ),
            (model.as_str(), "12345678", "1.31")
        );
        assert_eq!(info.output_rate_hz, Some(1200));
        assert_eq!(s.rated(), Simulator::model_rated(model).unwrap());
        assert_eq!(s.port(), sim.port());
    }
}

#[test]
fn v113_product_info_and_published_ratings() {
    let sim = Simulator::start_with(&sim_options(&[("model", "CFS034CA301U")])).unwrap();
    let s = Sensor::open(sim.port()).unwrap();
    assert_eq!(s.product_info().firmware, "1.13");
    assert_eq!(s.product_info().serial, "00000001");
    assert_eq!(s.product_info().output_rate_hz, None);
    assert_eq!(s.rated().force, [150.0, 150.0, 300.0]);
    assert_eq!(s.rated().torque, [4.0, 4.0, 4.0]);
    assert_eq!(s.rated().axes(), [150.0, 150.0, 300.0, 4.0, 4.0, 4.0]);
}

#[test]
fn one_second_at_1200_hz_without_loss() {
    let sim = Simulator::start().unwrap();
    let mut s = Sensor::open(sim.port()).unwrap();
    let rec = s.record(Duration::from_secs(1)).unwrap();
    let n = rec.len();
    assert!((1176..=1224).contains(&n), "{n} samples");
    // sequence-exact accounting: every sample numbered, none lost, none twice
    assert!(steps_all_one(&rec));
    assert_eq!(rec.missing(), 0);
    for col in [
        rec.t_utc.len(),
        rec.raw.len(),
        rec.zeroed.len(),
        rec.si.len(),
        rec.status.len(),
        rec.flags.len(),
        rec.seq.len(),
    ] {
        assert_eq!(col, n);
    }
    assert!(rec.t.windows(2).all(|w| w[1] >= w[0]));
    let span = rec.t[n - 1] - rec.t[0];
    assert!((span - 1.0).abs() < 0.05, "span {span}");
    let rated = s.rated().axes();
    for i in [0, n / 2, n - 1] {
        for (a, r) in rated.iter().enumerate() {
            assert!((rec.si[i][a] - f64::from(rec.raw[i][a]) * r / 10000.0).abs() < 1e-9);
        }
        assert_eq!(rec.force(i), [rec.si[i][0], rec.si[i][1], rec.si[i][2]]);
        assert_eq!(rec.torque(i), [rec.si[i][3], rec.si[i][4], rec.si[i][5]]);
    }
    assert_eq!(rec.gaps(), 0);
    assert!(!s.streaming());
    assert!(
        rec.metadata_json.contains("\"model\":\"PFS055YA501U6\""),
        "{}",
        rec.metadata_json
    );
    let h = s.health();
    assert_eq!(h.nominal_hz, 1200.0);
    assert!(h.received >= n as u64 && h.lost == 0);
    assert_eq!(sim.stats().samples_dropped, 0);
}

#[test]
fn record_count_and_in_a_running_stream() {
    let mut s = open_sim(&[], Options::new());
    let rec = s.record_count(500).unwrap();
    assert_eq!(rec.len(), 500);
    assert_eq!(rec.missing(), 0);
    s.start().unwrap();
    let a = s.record_count(300).unwrap();
    let b = s.record_count(300).unwrap();
    assert!(s.streaming()); // record() leaves a stream it did not start running
                            // the second continues the first: nothing lost between them
    assert_eq!(b.seq[0], a.seq[299].wrapping_add(1));
    s.stop().unwrap();
    assert_eq!(s.record_count(0).unwrap_err().kind(), ErrorKind::Arg);
    assert_eq!(s.record(Duration::ZERO).unwrap_err().kind(), ErrorKind::Arg);
}

#[test]
fn handshake_read() {
    let mut s = open_sim(
        &[("constant", "true"), ("amplitude", "0.5")],
        Options::new(),
    );
    let x = s.read().unwrap();
    let rated = s.rated().axes();
    assert_eq!(x.raw, [5000; 6]);
    for (v, r) in x.si.iter().zip(rated) {
        assert!((v - 0.5 * r).abs() < 1e-9);
    }
    assert_eq!(x.status, 0);
    assert!((x.t - unsafe { sys::lep_monotonic_seconds() }).abs() < 5.0);
    assert_eq!(x.zeroed, [5000.0; 6]);
    s.start().unwrap();
    assert_eq!(s.read().unwrap_err().kind(), ErrorKind::State);
    s.stop().unwrap();
    // with the session's units: the tare in force applies to a lone sample too
    assert_eq!(s.tare(20).unwrap(), [5000.0; 6]);
    let x = s.read().unwrap();
    assert_eq!((x.raw, x.zeroed), ([5000; 6], [0.0; 6]));
    assert!(x.si.iter().all(|v| v.abs() < 1e-9));
}

#[test]
fn tare_and_untare() {
    let mut s = open_sim(
        &[("constant", "true"), ("amplitude", "0.25")],
        Options::new(),
    );
    assert!(!s.tared());
    assert_eq!(s.tare(100).unwrap(), [2500.0; 6]);
    assert!(s.tared());
    assert!(s.take_events().iter().any(|e| e.kind
        == EventKind::Tare {
            offsets: [2500.0; 6]
        }));
    let rec = s.record_count(100).unwrap();
    assert!(rec.zeroed.iter().all(|z| *z == [0.0; 6]));
    assert!(rec.si.iter().all(|v| v.iter().all(|x| x.abs() < 1e-9)));
    assert!(rec.raw.iter().all(|r| *r == [2500; 6]));
    s.untare().unwrap();
    assert!(!s.tared());
    assert_eq!(s.tare_offsets(), [0.0; 6]);
    let rec = s.record_count(50).unwrap();
    assert!(rec.zeroed.iter().all(|z| *z == [2500.0; 6]));
    // the untare (done while stopped) is an event at the recording's first row
    let tares: Vec<_> = rec
        .events
        .iter()
        .filter(|e| matches!(e.kind, EventKind::Tare { .. }))
        .collect();
    assert_eq!(tares.len(), 1);
    assert_eq!(
        (tares[0].kind, tares[0].sample),
        (EventKind::Tare { offsets: [0.0; 6] }, 0)
    );
    assert_eq!(s.tare(0).unwrap_err().kind(), ErrorKind::Arg);
}

#[test]
fn tare_beside_the_stream_never_stalls() {
    let mut s = open_sim(
        &[("constant", "true"), ("amplitude", "0.25")],
        Options::new(),
    );
    let mut st = s.stream().unwrap();
    let mut samples = Vec::new();
    while samples.len() < 900 {
        samples.push(st.next().unwrap().unwrap());
        if samples.len() == 200 {
            st.begin_tare(100).unwrap();
        }
    }
    let events = st.take_events();
    drop(st);
    assert!(!s.streaming());
    assert!(
        samples
            .windows(2)
            .all(|w| w[1].seq == w[0].seq.wrapping_add(1)),
        "nothing lost, no stall"
    );
    let taring: Vec<usize> = (0..samples.len())
        .filter(|&i| samples[i].taring())
        .collect();
    assert_eq!(taring.len(), 100);
    assert!(taring[0] >= 200);
    let after = &samples[taring[99] + 1..];
    assert!(after.len() > 500);
    assert!(after
        .iter()
        .all(|x| x.si.iter().all(|v| v.abs() < 1e-9) && x.zeroed == [0.0; 6]));
    let tares: Vec<_> = events
        .iter()
        .filter(|e| matches!(e.kind, EventKind::Tare { .. }))
        .collect();
    assert_eq!(tares.len(), 1);
    assert_eq!(tares[0].sample, taring[99] as u64 + 1);
}

#[test]
fn gaps_from_dropped_samples() {
    let mut s = open_sim(&[("drop", "0.02"), ("seed", "5")], Options::new());
    let rec = s.record(Duration::from_secs(1)).unwrap();
    let gaps: Vec<u32> = rec
        .events
        .iter()
        .filter_map(|e| match e.kind {
            EventKind::Gap { lost, from, to } => {
                assert!(to > from);
                Some(lost)
            }
            _ => None,
        })
        .collect();
    assert!(!gaps.is_empty());
    assert_eq!(rec.gaps(), gaps.len());
    assert_eq!(
        gaps.iter().map(|&l| u64::from(l)).sum::<u64>(),
        rec.missing()
    );
    let h = s.health();
    assert!(h.gaps >= gaps.len() as u64 && h.lost >= rec.missing());
    let dropped = s.simulator().unwrap().stats().samples_dropped;
    assert!(rec.missing() > 0 && rec.missing() <= dropped);
}

#[test]
fn a_stall_shorter_than_the_data_timeout_is_a_gap() {
    let mut s = open_sim(
        &[("stall", "300"), ("stall-after", "0.3")],
        Options::new().timeout(Duration::from_millis(100)),
    );
    let rec = s.record(Duration::from_millis(1200)).unwrap();
    assert!(rec.len() > 500);
    // the 0.3 s hole, three times the answer timeout: a gap, no error; its
    // loss is exact (sequence numbers), its length in arrival times is not
    // (a loaded machine delivers the samples before it late)
    let lost: u64 = rec
        .events
        .iter()
        .filter_map(|e| match e.kind {
            EventKind::Gap { lost, .. } => Some(u64::from(lost)),
            _ => None,
        })
        .sum();
    assert_eq!(lost, rec.missing());
    assert!((300..=400).contains(&lost), "{lost} lost");
    assert!(lost <= s.simulator().unwrap().stats().samples_skipped);
    let max_gap = s.health().max_gap_s;
    assert!(max_gap >= 0.15, "{max_gap}");
}

#[test]
fn a_pulled_cable_ends_the_recording_and_keeps_the_samples() {
    let sim = Simulator::start().unwrap();
    let mut s = Sensor::open(sim.port()).unwrap();
    let err = std::thread::scope(|scope| {
        scope.spawn(|| {
            std::thread::sleep(Duration::from_millis(300));
            sim.hangup();
        });
        s.record(Duration::from_secs(5)).unwrap_err()
    });
    assert_eq!(err.kind(), ErrorKind::Disconnected, "{err}");
    assert_eq!(err.code(), sys::LEP_E_DISCONNECTED);
    assert!(err.to_string().contains(sim.port()), "{err}");
    let partial = err.recording().unwrap();
    assert!(partial.len() > 100, "{}", partial.len());
    assert_eq!(partial.missing(), 0);
    assert!(partial.events.iter().any(|e| matches!(
        e.kind,
        EventKind::Disconnected {
            cause: ErrorKind::Disconnected,
            ..
        }
    )));
    assert_eq!(sim.stats().hangups, 1);
}

#[test]
fn a_pulled_cable_ends_the_iterator_with_an_error() {
    let mut s = open_sim(&[("hangup-after", "0.3")], Options::new());
    let mut ok = 0;
    let mut last = None;
    for x in s.stream().unwrap() {
        match x {
            Ok(_) => ok += 1,
            Err(e) => last = Some(e),
        }
    }
    assert!(ok > 100);
    assert_eq!(last.unwrap().kind(), ErrorKind::Disconnected);
}

#[test]
fn reconnect_marks_the_gap() {
    let mut s = open_sim(
        &[("hangup-after", "0.3"), ("reopen-after", "300")],
        Options::new().reconnect(true),
    );
    let rec = s.record(Duration::from_secs(2)).unwrap();
    let kinds: Vec<_> = rec.events.iter().map(|e| e.kind).collect();
    assert!(
        kinds
            .iter()
            .any(|k| matches!(k, EventKind::Disconnected { .. })),
        "{kinds:?}"
    );
    assert!(
        kinds
            .iter()
            .any(|k| matches!(k, EventKind::Reconnected { to, from, .. } if to > from)),
        "{kinds:?}"
    );
    assert!(rec.gaps() > 0);
    assert_eq!(s.health().reconnects, 1);
}

#[test]
fn the_data_timeout_ends_the_recording() {
    let mut s = open_sim(
        &[("stall", "2500"), ("stall-after", "0.2")],
        Options::new().data_timeout(Duration::from_millis(500)),
    );
    let t0 = Instant::now();
    let err = s.record(Duration::from_secs(10)).unwrap_err();
    // given up after the data timeout, not the 10 s (the stop then waits for the stalled sensor)
    assert!(t0.elapsed() < Duration::from_secs(6));
    assert_eq!(err.kind(), ErrorKind::Lost, "{err}");
    assert_eq!(err.code(), sys::LEP_E_LOST);
    let partial = err.into_recording().unwrap();
    assert!(partial.len() > 100 && partial.t[partial.len() - 1] - partial.t[0] < 1.0);
    assert!(partial.events.iter().any(|e| matches!(
        e.kind,
        EventKind::Disconnected {
            cause: ErrorKind::Timeout,
            ..
        }
    )));
}

#[test]
fn errors_carry_the_library_code_and_message() {
    let e = Sensor::open("/dev/leptrino-no-such-port").unwrap_err();
    assert_eq!(
        (e.kind(), e.code()),
        (ErrorKind::NotFound, sys::LEP_E_NOT_FOUND)
    );
    assert!(e.message().contains("/dev/leptrino-no-such-port"), "{e}");
    let file = std::env::temp_dir().join(format!("leptrino-rust-test-{}", std::process::id()));
    std::fs::write(&file, b"not a tty").unwrap();
    let e = Sensor::open(file.to_str().unwrap()).unwrap_err();
    std::fs::remove_file(&file).unwrap();
    assert_eq!(e.kind(), ErrorKind::NotTty, "{e}");
    // options: the library's own check and message
    let mut o = SimOptions::new();
    let e = o.set("amplitude", 5).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::Arg);
    assert!(e.message().contains("amplitude"), "{e}");
    assert_eq!(
        o.set("no-such-option", 1).unwrap_err().kind(),
        ErrorKind::Arg
    );
    let e = Sensor::open_with("/dev/null", &Options::new().decimate(0)).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::Arg, "{e}");
    assert_eq!(
        Simulator::model_rated("XYZ").unwrap_err().kind(),
        ErrorKind::Arg
    );
    // every LEP_E_* of the header, each with the library's description
    assert!(ErrorKind::ALL.len() >= 23 && ErrorKind::ALL.contains(&ErrorKind::Stalled));
    for &k in ErrorKind::ALL {
        assert_eq!(ErrorKind::from_code(k.code()), Some(k));
        let text = unsafe { std::ffi::CStr::from_ptr(sys::lep_strerror(k.code())) };
        assert!(
            !text.to_bytes().is_empty() && text.to_bytes() != b"unknown error",
            "{k:?}"
        );
    }
}

#[test]
fn send_where_the_contract_allows() {
    fn send<T: Send>() {}
    fn send_sync<T: Send + Sync>() {}
    send::<Sensor>();
    send_sync::<Control>();
    send_sync::<Simulator>();
    send_sync::<Error>();
    send_sync::<Recording>();
    send_sync::<Options>();
    send_sync::<SimOptions>();
    // a sensor opened here, driven there, while a third thread tares it
    let s = open_sim(
        &[("constant", "true"), ("amplitude", "0.1")],
        Options::new(),
    );
    let control = s.control();
    let reader = std::thread::spawn(move || {
        let mut s = s;
        s.start().unwrap();
        let rec = s.record_count(1200).unwrap();
        s.stop().unwrap();
        rec
    });
    std::thread::sleep(Duration::from_millis(200));
    control.begin_tare(60).unwrap();
    let rec = reader.join().unwrap();
    assert!(steps_all_one(&rec));
    assert!(
        rec.events.iter().any(|e| e.kind
            == EventKind::Tare {
                offsets: [1000.0; 6]
            }),
        "{:?}",
        rec.events
    );
    assert_eq!(control.tare_offsets(), [1000.0; 6]);
}

#[test]
fn the_sample_iterator_stops_the_stream_it_started() {
    let sim = Simulator::start().unwrap();
    let mut s = Sensor::open(sim.port()).unwrap();
    let got: Vec<_> = s.stream().unwrap().take(50).map(Result::unwrap).collect();
    assert!(got
        .windows(2)
        .all(|w| w[1].seq == w[0].seq.wrapping_add(1) && w[1].t >= w[0].t));
    assert!(!s.streaming());
    std::thread::sleep(Duration::from_millis(50));
    assert!(!sim.stats().streaming);
    assert_eq!(s.stream().unwrap().take(7).count(), 7);
    assert!(s.read().is_ok());
}

#[test]
fn limits_are_events() {
    // a constant load of 0.25 x rated: Fz of the default model is 125 N
    let mut s = open_sim(
        &[("constant", "true"), ("amplitude", "0.25")],
        Options::new(),
    );
    s.set_limits([0.0, 0.0, 100.0, 0.0, 0.0, 0.0]).unwrap();
    let rec = s.record_count(100).unwrap();
    let exceeded: Vec<_> = rec
        .events
        .iter()
        .filter_map(|e| match e.kind {
            EventKind::LimitExceeded { axes, wrench } => Some((e.sample, axes, wrench[2])),
            _ => None,
        })
        .collect();
    assert_eq!(exceeded.len(), 1, "{:?}", rec.events);
    assert_eq!((exceeded[0].0, exceeded[0].1), (0, 1 << 2));
    assert!((exceeded[0].2 - 0.25 * s.rated().force[2]).abs() < 1e-9);
    assert_eq!(s.set_limits([-1.0; 6]).unwrap_err().kind(), ErrorKind::Arg);
}
