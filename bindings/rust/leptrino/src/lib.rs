//! Leptrino 6-axis force/torque sensors (PFS/CFS lines) from Rust, through
//! libleptrino's host session: start-up recovery, identity and rated values,
//! tare, host low-pass, decimation, output frame, gap detection with exact
//! loss counts, reconnects, health and metadata, all done once in C
//! (`leptrino/session.h`) for every language. This crate reads the session's
//! samples into plain vectors and its numbers and texts into Rust values.
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
mod options;
mod payload;
mod sensor;
mod sim;
mod values;

pub use leptrino_sys as sys;

pub use error::{Error, ErrorKind, Result};
pub use options::Options;
pub use payload::{identify_payload, pose_mean, standard_gravity, PayloadFit};
pub use sensor::{Control, Sensor, Stream};
pub use sim::{SimOptions, SimStats, Simulator, VirtualSensor};
pub use values::{
    ClientStats, Event, EventKind, Health, Metadata, Payload, PortInfo, ProductInfo, Rated,
    Recording, Sample,
};

/// The serial ports on this machine (`lep_port_list_*`): path, stable by-id
/// path, USB description and ids, and whether it is likely a sensor. A
/// machine without serial ports gives an empty list.
///
/// ```
/// for p in leptrino::list_ports()? {
///     println!("{} {} {:04x}:{:04x} {}", p.path, p.by_id, p.vid, p.pid,
///              if p.likely_sensor { "(sensor?)" } else { "" });
/// }
/// # Ok::<(), leptrino::Error>(())
/// ```
pub fn list_ports() -> Result<Vec<PortInfo>> {
    let mut l: *mut sys::lep_port_list = std::ptr::null_mut();
    // SAFETY: valid out pointer.
    error::check(
        unsafe { sys::lep_port_list_new(&mut l) },
        "listing serial ports",
    )?;
    let text = |p: *const std::ffi::c_char| options::static_str(p).to_owned();
    // SAFETY: l is a list made above, read by index below its count, its
    // strings copied before it is freed.
    let ports = unsafe {
        (0..sys::lep_port_list_count(l))
            .map(|i| PortInfo {
                path: text(sys::lep_port_list_path(l, i)),
                by_id: text(sys::lep_port_list_by_id(l, i)),
                description: text(sys::lep_port_list_description(l, i)),
                vid: u16::try_from(sys::lep_port_list_vid(l, i)).unwrap_or(0),
                pid: u16::try_from(sys::lep_port_list_pid(l, i)).unwrap_or(0),
                likely_sensor: sys::lep_port_list_likely_sensor(l, i) == 1,
            })
            .collect()
    };
    // SAFETY: made by lep_port_list_new, freed once.
    unsafe { sys::lep_port_list_free(l) };
    Ok(ports)
}

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
