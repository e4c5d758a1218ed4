//! The safe API against the in-process virtual sensor, through a real pty:
//! identity, rated values, recording without loss, tare, faults, a pulled
//! cable, reconnects, errors, options by name, the live options (low-pass,
//! frame, payload, gravity), metadata and health by name. The scenarios of the Python suite
//! (bindings/python/tests/test_sensor.py, test_session.py).

use std::time::{Duration, Instant};

use leptrino::{
    identify_payload, standard_gravity, sys, Control, Error, ErrorKind, EventKind, Options,
    Payload, Recording, Sensor, SimOptions, Simulator,
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
fn events_sit_at_rows_of_a_recording_in_a_running_stream() {
    let mut s = open_sim(
        &[("constant", "true"), ("amplitude", "0.25")],
        Options::new(),
    );
    s.start().unwrap();
    let before = s.record_count(300).unwrap(); // rows the next recording does not hold
    assert_eq!(before.len(), 300);
    s.control().begin_tare(50).unwrap();
    let rec = s.record_count(400).unwrap();
    let tares: Vec<_> = rec
        .events
        .iter()
        .filter(|e| matches!(e.kind, EventKind::Tare { .. }))
        .collect();
    assert_eq!(tares.len(), 1);
    // the library's row in the batch, counted in this recording's rows: the
    // first row the new offset zeroes, after the last one averaged
    let i = tares[0].sample as usize;
    assert!(i > 0 && i < rec.len(), "tare at row {i}");
    assert_eq!(rec.zeroed[i], [0.0; 6]);
    assert_eq!(rec.zeroed[i - 1], [2500.0; 6]);
    // an untare while stopped sits at the next stream's first row
    s.stop().unwrap();
    s.untare().unwrap();
    let mut it = s.stream().unwrap();
    assert!(it.next().unwrap().is_ok());
    let ev = it.take_events();
    assert_eq!(ev.len(), 1);
    assert_eq!(
        (ev[0].kind, ev[0].sample),
        (EventKind::Tare { offsets: [0.0; 6] }, 0)
    );
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
                assert!(to > from, "gap from {from} to {to} ({lost} lost)");
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

fn mean(rec: &Recording, axis: usize) -> f64 {
    rec.si.iter().map(|v| v[axis]).sum::<f64>() / rec.len() as f64
}

#[test]
fn options_by_name_from_the_library_table() {
    let names = Options::names();
    for n in [
        "port",
        "timeout",
        "data-timeout",
        "lowpass",
        "payload",
        "gravity",
        "limit",
    ] {
        assert!(names.contains(&n), "{n} missing from {names:?}");
    }
    assert!(names.iter().all(|n| !n.starts_with("sim-")));
    let sim_names = SimOptions::names();
    for n in [
        "model",
        "rate",
        "drop",
        "payload",
        "gravity",
        "link",
        "usb-packets",
        "ftdi-latency",
        "ppm",
    ] {
        assert!(sim_names.contains(&n), "{n} missing from {sim_names:?}");
    }

    let mut o = Options::new().lowpass(40.0).decimate(2);
    assert_eq!(o.get("decimate").unwrap(), "2");
    assert_eq!(o.get("lowpass").unwrap().parse::<f64>().unwrap(), 40.0);
    o.set("data_timeout", 700)
        .unwrap()
        .set("reconnect", true)
        .unwrap();
    assert_eq!(o.get("data-timeout").unwrap(), "700");
    assert_eq!(o.get("reconnect").unwrap(), "1");
    let e = o.set("lowpas", 1).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::Arg);
    assert!(e.message().contains("lowpas"), "{e}");
    let e = o.set("lowpass", "fast").unwrap_err();
    assert!(e.message().contains("lowpass"), "{e}");
    assert!(format!("{o:?}").contains("data-timeout"));
    // a copy is a handle of its own
    let copy = o.clone();
    o.set("decimate", 3).unwrap();
    assert_eq!(copy.get("decimate").unwrap(), "2");

    // the "sim-" prefix is optional on SimOptions
    let mut so = SimOptions::new();
    so.set("sim-rate", 600).unwrap().set("sim_seed", 9).unwrap();
    assert_eq!(so.get("rate").unwrap().parse::<f64>().unwrap(), 600.0);
    assert_eq!(so.get("seed").unwrap(), "9");

    // open_sim: the session's options from Options, the sim's from SimOptions
    let s = Sensor::open_sim(&so, &copy).unwrap();
    assert_eq!(s.get("decimate").unwrap(), "2");
    assert_eq!(s.lowpass(), 40.0);
    assert_eq!(s.metadata().nominal_hz, 600.0);
    // a builder's refusal comes back at open, with the library's message
    let e = Sensor::open_sim(&so, &Options::new().lowpass(-1.0)).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::Arg);
    assert!(e.message().contains("lowpass"), "{e}");
}

#[test]
fn live_options_low_pass_and_frame() {
    let mut s = open_sim(&[], Options::new().lowpass(50.0));
    assert_eq!(s.lowpass(), 50.0);
    assert_eq!(s.metadata().lowpass_hz, 50.0);
    assert!(!s.metadata().lowpass_name.is_empty());
    s.set_lowpass(0.0).unwrap();
    assert_eq!(s.lowpass(), 0.0);
    assert_eq!(s.set_lowpass(1000.0).unwrap_err().kind(), ErrorKind::Value);
    assert_eq!(s.lowpass(), 0.0);
    s.set("lowpass", 20).unwrap();
    assert_eq!(s.lowpass(), 20.0);
    assert_eq!(
        s.set("decimate", 2).unwrap_err().kind(),
        ErrorKind::State,
        "not a live option"
    );

    let swap = [0.0, 1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, -1.0]; // x <-> y, z flipped
    s.set_frame(swap, [0.0, 0.0, 0.1]).unwrap();
    assert_eq!(s.frame(), (swap, [0.0, 0.0, 0.1]));
    let m = s.metadata();
    assert_eq!((m.rotation, m.shift_m), (swap, [0.0, 0.0, 0.1]));
    // not orthonormal: refused, and the frame stays
    let e = s.set_frame([0.5, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0], [0.0; 3]);
    assert_eq!(e.unwrap_err().kind(), ErrorKind::Value);
    // beyond the option's range: the table's check
    let e = s.set_frame([2.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0], [0.0; 3]);
    assert_eq!(e.unwrap_err().kind(), ErrorKind::Arg);
    assert_eq!(s.frame(), (swap, [0.0, 0.0, 0.1]));
    // a bad shift leaves the rotation too
    let identity = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0];
    assert!(s.set_frame(identity, [f64::NAN, 0.0, 0.0]).is_err());
    assert_eq!(s.frame().0, swap);

    // latency is the reading thread's
    assert_eq!(s.set("latency", 5).unwrap_err().kind(), ErrorKind::State);
    s.set_latency(Duration::from_millis(5)).unwrap();
    assert_eq!(s.latency(), Duration::from_millis(5));
    let rec = s.record_count(50).unwrap();
    assert_eq!(rec.len(), 50);
    assert_eq!(
        s.latency(),
        Duration::from_millis(5),
        "record() puts it back"
    );
}

#[test]
fn payload_and_gravity_compensation() {
    // the virtual sensor carries a 1 kg tool 0.1 m up its z axis, tilted so
    // that gravity runs along -x: F = (-g, 0, 0), M = c x F = (0, -0.1 g, 0)
    let g = standard_gravity();
    let tilted = format!("{},0,0", -g);
    let sim = sim_options(&[
        ("constant", "true"),
        ("amplitude", "0"),
        ("payload", "1,0,0,0.1"),
        ("gravity", &tilted),
    ]);
    let mut s = Sensor::open_sim(&sim, &Options::new()).unwrap();
    let resolution = s.rated().axes().map(|r| r / 10000.0);
    let rec = s.record_count(50).unwrap();
    assert!(
        (mean(&rec, 0) + g).abs() <= resolution[0],
        "{}",
        mean(&rec, 0)
    );
    assert!((mean(&rec, 4) + 0.1 * g).abs() <= resolution[4]);

    let tool = Payload::new(1.0, [0.0, 0.0, 0.1]);
    s.set_payload(Some(tool)).unwrap();
    s.set_gravity([-g, 0.0, 0.0]).unwrap();
    assert_eq!(s.payload(), Some(tool));
    assert_eq!(s.gravity(), [-g, 0.0, 0.0]);
    let m = s.metadata();
    assert_eq!((m.payload, m.gravity), (Some(tool), [-g, 0.0, 0.0]));
    let rec = s.record_count(50).unwrap();
    for (a, r) in resolution.iter().enumerate() {
        assert!(mean(&rec, a).abs() <= *r, "axis {a}: {}", mean(&rec, a));
    }
    // raw and zeroed counts stay as measured
    assert!(rec.raw[0][0] < 0);
    assert_eq!(
        tool.wrench([-g, 0.0, 0.0]).unwrap(),
        [-g, 0.0, 0.0, 0.0, -0.1 * g, 0.0]
    );

    s.set_payload(None).unwrap();
    assert_eq!(s.payload(), None);
    assert_eq!(
        s.set_payload(Some(Payload::new(-1.0, [0.0; 3])))
            .unwrap_err()
            .kind(),
        ErrorKind::Arg
    );
    assert!(s.set_gravity([f64::INFINITY, 0.0, 0.0]).is_err());
    // also as options at open
    let s = Sensor::open_sim(
        &sim,
        &Options::new()
            .payload(Some(tool))
            .gravity([-g, 0.0, 0.0])
            .limits([0.0, 0.0, 100.0, 0.0, 0.0, 0.0]),
    )
    .unwrap();
    assert_eq!(s.payload(), Some(tool));
    assert_eq!(s.limits(), [0.0, 0.0, 100.0, 0.0, 0.0, 0.0]);
}

#[test]
fn identify_a_payload_from_poses() {
    let g = standard_gravity();
    let tool = Payload::new(0.8, [0.01, -0.02, 0.06]);
    let bias = [0.5, -0.3, 1.0, 0.02, 0.01, -0.03];
    let poses = [
        [0.0, 0.0, -g],
        [-g, 0.0, 0.0],
        [0.0, -g, 0.0],
        [0.0, g * 0.6, -g * 0.8],
    ];
    let wrench: Vec<[f64; 6]> = poses
        .iter()
        .map(|p| {
            let w = tool.wrench(*p).unwrap();
            std::array::from_fn(|i| w[i] + bias[i])
        })
        .collect();
    let fit = identify_payload(&poses, &wrench).unwrap();
    assert!((fit.payload.mass_kg - 0.8).abs() < 1e-9, "{fit:?}");
    for i in 0..3 {
        assert!((fit.payload.com_m[i] - tool.com_m[i]).abs() < 1e-9);
        assert!((fit.force_bias_n[i] - bias[i]).abs() < 1e-9);
        assert!((fit.torque_bias_nm[i] - bias[3 + i]).abs() < 1e-9);
    }
    assert_eq!(fit.poses, 4);
    assert!(fit.spread > 0.1);
    // one direction only: the library refuses, and says why
    let e = identify_payload(&poses[..1].repeat(3), &wrench[..1].repeat(3)).unwrap_err();
    assert_eq!(e.kind(), ErrorKind::Value, "{e}");
    assert!(!e.message().is_empty());
    assert_eq!(
        identify_payload(&poses, &wrench[..2]).unwrap_err().kind(),
        ErrorKind::Arg
    );
}

#[test]
fn metadata_and_health_by_name() {
    let sim =
        Simulator::start_with(&sim_options(&[("model", "CFS034CA301U"), ("filter", "1")])).unwrap();
    let mut s = Sensor::open(sim.port()).unwrap();
    let m = s.metadata();
    assert_eq!(&m.product, s.product_info());
    assert_eq!(m.rated, s.rated());
    assert_eq!((m.sensor_filter, s.filter()), (Some(1), Some(1)));
    assert_eq!(m.sensor_filter_label, s.filter_label());
    assert_eq!(m.port, sim.port());
    assert!(!m.sim, "a port, not a session's own virtual sensor");
    assert_eq!(m.library_version, leptrino::library_version());
    assert_eq!((m.nominal_hz, m.decimate, m.tared), (1200.0, 1, false));
    assert!(!m.protocol.is_empty());
    assert!(s
        .metadata_json()
        .unwrap()
        .contains("\"serial\":\"00000001\""));

    let rec = s.record_count(300).unwrap();
    let h = s.health();
    let fields = h.fields();
    assert!(fields.len() >= 31, "{fields:?}");
    assert_eq!(h.get("received"), Some(h.received as f64));
    assert_eq!(h.get("delivered"), Some(rec.len() as f64));
    assert_eq!(h.get("bcc_errors"), Some(h.client.bcc_errors as f64));
    assert!(h.client.messages > 0 && h.client.samples >= 300);
    assert_eq!(h.get("no-such-field"), None);
    let st = sim.stats();
    let by_name = st.fields();
    assert!(by_name.contains(&("samples_sent", st.samples_sent)));
    assert!(st.samples_sent >= 300 && st.filter == 1);
}

#[test]
fn the_filter_through_the_session_client() {
    let sim = Simulator::start().unwrap();
    let mut s = Sensor::open(sim.port()).unwrap();
    assert_eq!(s.filter(), Some(0));
    assert_eq!(s.set_filter(4).unwrap_err().kind(), ErrorKind::Value);
    s.start().unwrap();
    assert_eq!(s.set_filter(3).unwrap_err().kind(), ErrorKind::State);
    s.stop().unwrap();
    s.set_filter(3).unwrap();
    let st = sim.stats();
    assert_eq!((st.filter, st.filter_pending), (0, 3));
    assert_eq!(s.filter(), Some(0), "the code read at open");
    sim.power_cycle(); // applied on the virtual sensor's thread
    let t0 = Instant::now();
    while sim.stats().filter != 3 && t0.elapsed() < Duration::from_secs(2) {
        std::thread::sleep(Duration::from_millis(10));
    }
    assert_eq!(sim.stats().filter, 3);
}

#[test]
fn a_held_output_arrives_late_and_whole() {
    let sim = Simulator::start().unwrap();
    let mut s = Sensor::open(sim.port()).unwrap();
    s.start().unwrap();
    let a = s.record_count(120).unwrap();
    sim.hold(Duration::from_millis(300));
    let t0 = Instant::now();
    let b = s.record_count(600).unwrap();
    s.stop().unwrap();
    assert!(t0.elapsed() >= Duration::from_millis(300));
    assert_eq!(b.seq[0], a.seq[119].wrapping_add(1));
    assert_eq!(b.missing(), 0);
    assert_eq!(sim.stats().samples_blocked, 0);
}

#[test]
fn the_port_list() {
    // the machine may have no serial port: an empty list, not an error
    for p in leptrino::list_ports().unwrap() {
        assert!(p.path.starts_with("/dev/"), "{p:?}");
    }
}
