//! Stream a Leptrino sensor and print force and torque.
//!
//!     cargo run --example stream -- --sim                 # the in-process virtual sensor
//!     cargo run --example stream -- /dev/ttyACM0 --tare 100 --seconds 5
//!
//! Options: --sim, --seconds S (default 2), --tare N (samples), --every N
//! (print every Nth sample, default 120: ten lines a second at 1200 Hz).

use std::process::ExitCode;
use std::time::Duration;

use leptrino::{EventKind, Options, Sensor, SimOptions};

struct Args {
    port: Option<String>,
    sim: bool,
    seconds: f64,
    tare: u32,
    every: usize,
}

fn parse() -> Result<Args, String> {
    let mut a = Args {
        port: None,
        sim: false,
        seconds: 2.0,
        tare: 0,
        every: 120,
    };
    let mut it = std::env::args().skip(1);
    while let Some(arg) = it.next() {
        let mut value = |name: &str| it.next().ok_or(format!("{name} needs a value"));
        match arg.as_str() {
            "--sim" => a.sim = true,
            "--seconds" => {
                a.seconds = value("--seconds")?
                    .parse()
                    .map_err(|e| format!("--seconds: {e}"))?
            }
            "--tare" => {
                a.tare = value("--tare")?
                    .parse()
                    .map_err(|e| format!("--tare: {e}"))?
            }
            "--every" => {
                a.every = value("--every")?
                    .parse()
                    .map_err(|e| format!("--every: {e}"))?
            }
            "-h" | "--help" => return Err(String::new()),
            p if !p.starts_with('-') && a.port.is_none() => a.port = Some(p.to_owned()),
            other => return Err(format!("unknown argument {other}")),
        }
    }
    if a.sim == a.port.is_some() {
        return Err("give a port or --sim".into());
    }
    if !(a.seconds > 0.0 && a.seconds.is_finite()) || a.every == 0 {
        return Err("--seconds must be > 0 and --every >= 1".into());
    }
    Ok(a)
}

fn run(a: &Args) -> leptrino::Result<()> {
    let mut sensor = match &a.port {
        Some(port) => Sensor::open(port)?,
        None => Sensor::open_sim(&SimOptions::new(), &Options::new())?,
    };
    let info = sensor.product_info();
    println!(
        "# {} serial {} firmware {} on {}",
        info.model,
        info.serial,
        info.firmware,
        sensor.port()
    );
    let r = sensor.rated();
    println!("# rated force {:?} N, torque {:?} N m", r.force, r.torque);
    if a.tare > 0 {
        println!("# tare offsets {:?} counts", sensor.tare(a.tare)?);
    }
    println!("t_s,fx_N,fy_N,fz_N,mx_Nm,my_Nm,mz_Nm,status");
    let mut n = 0usize;
    let mut t0 = None;
    let end = Duration::from_secs_f64(a.seconds).as_secs_f64();
    let mut stream = sensor.stream()?;
    for x in stream.by_ref() {
        let x = x?;
        let t = x.t - *t0.get_or_insert(x.t);
        if t >= end {
            break;
        }
        if n % a.every == 0 {
            let s = x.si;
            println!(
                "{t:.6},{:.4},{:.4},{:.4},{:.5},{:.5},{:.5},{}",
                s[0], s[1], s[2], s[3], s[4], s[5], x.status
            );
        }
        n += 1;
    }
    for e in stream.events() {
        match e.kind {
            EventKind::Gap { lost, .. } => {
                println!("# gap before sample {}: {lost} lost", e.sample)
            }
            k => println!("# event at sample {}: {k:?}", e.sample),
        }
    }
    drop(stream);
    let h = sensor.health();
    println!(
        "# {n} samples in {:.2} s ({:.1} Hz measured), {} lost in {} gaps",
        a.seconds, h.measured_hz, h.lost, h.gaps
    );
    Ok(())
}

fn main() -> ExitCode {
    let args = match parse() {
        Ok(a) => a,
        Err(msg) => {
            if !msg.is_empty() {
                eprintln!("stream: {msg}");
            }
            eprintln!("usage: stream (PORT | --sim) [--seconds S] [--tare N] [--every N]");
            return ExitCode::from(2);
        }
    };
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("stream: {e}");
            ExitCode::FAILURE
        }
    }
}
