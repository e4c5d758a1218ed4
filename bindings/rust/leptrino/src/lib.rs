//! Leptrino 6-axis force/torque sensors (PFS/CFS lines) from Rust, through
//! libleptrino's host session: start-up recovery, identity and rated values,
//! tare, host low-pass, decimation, output frame, gap detection with exact
//! loss counts, reconnects, health and metadata, all done once in C
//! (`leptrino/session.h`) for every language. This crate moves the session's
//! batches into plain vectors and its structs into Rust values.
//!
//! ```
//! use std::time::Duration;
//! use leptrino::{Sensor, Simulator};
//!
//! // An in-process virtual sensor on a pseudo-terminal (a real sensor: its
//! // serial port, e.g. "/dev/ttyACM0").
//! let sim = Simulator::start()?;
//! let mut sensor = Sensor::open(sim.port())?;
//! let info = sensor.product_info();
//! println!("{} serial {} firmware {}", info.model, info.serial, info.firmware);
//!
//! sensor.tare(100)?;                                   // zero on 100 samples
//! let rec = sensor.record(Duration::from_millis(500))?; // half a second at 1.2 kHz
//! println!("{} samples, {} lost, Fz[0] = {:.3} N", rec.len(), rec.missing(), rec.force(0)[2]);
//!
//! for x in sensor.stream()?.take(10) {
//!     let x = x?;
//!     println!("{:.6} {:?}", x.t, x.force());
//! }
//! # assert!(rec.len() > 500 && rec.missing() == 0);
//! # Ok::<(), leptrino::Error>(())
//! ```
//!
//! The raw declarations are in [`sys`] (the `leptrino-sys` crate, generated
//! from the headers).
#![deny(missing_debug_implementations)]
#![warn(missing_docs)]

mod error;
mod sensor;
mod sim;
mod values;

pub use leptrino_sys as sys;

pub use error::{Error, ErrorKind, Result};
pub use sensor::{Control, Health, Options, Sensor, Stream};
pub use sim::{SimOptions, SimStats, Simulator, VirtualSensor};
pub use values::{Event, EventKind, ProductInfo, Rated, Recording, Sample};

/// The version of the library actually linked, e.g. "0.1.0".
pub fn library_version() -> &'static str {
    // SAFETY: a static NUL-terminated string.
    unsafe { std::ffi::CStr::from_ptr(sys::lep_version()) }
        .to_str()
        .unwrap_or("")
}

#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
