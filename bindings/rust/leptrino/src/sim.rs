//! The virtual sensor in-process (leptrino/sim.h): a pseudo-terminal served
//! by a C thread that behaves like a Leptrino sensor, with faults on demand.

use std::ffi::{c_char, CStr, CString};
use std::fmt;
use std::marker::{PhantomData, PhantomPinned};
use std::ptr::NonNull;
use std::time::Duration;

use leptrino_sys as sys;

use crate::error::{check_msg, Error, Result};
use crate::Rated;

/// Counters of what a virtual sensor did since it started (`lep_sim_stats`).
pub type SimStats = sys::lep_sim_stats;

/// Options of a virtual sensor: those of `leptrino-sim` and of the
/// `leptrino` tool's `--sim-*` options, from the same C table (names,
/// parsing, ranges and defaults are the library's).
///
/// ```
/// use leptrino::SimOptions;
/// let mut o = SimOptions::new();
/// o.set("model", "CFS034CA301U")?.set("drop", 0.01)?.set("output-rate-field", true)?;
/// assert_eq!(o.get("model")?, "CFS034CA301U");
/// let err = o.set("amplitude", 5).unwrap_err();
/// assert_eq!(err.kind(), leptrino::ErrorKind::Arg);
/// assert!(err.message().contains("amplitude"));
/// # Ok::<(), leptrino::Error>(())
/// ```
#[derive(Clone)]
pub struct SimOptions {
    pub(crate) raw: sys::lep_sim_options,
}

impl Default for SimOptions {
    fn default() -> Self {
        SimOptions::new()
    }
}

impl fmt::Debug for SimOptions {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut d = f.debug_struct("SimOptions");
        for name in SimOptions::names() {
            if let Ok(v) = self.get(name) {
                d.field(name, &v);
            }
        }
        d.finish()
    }
}

fn cstring(what: &str, s: &str) -> Result<CString> {
    CString::new(s).map_err(|_| Error::arg(format!("{what} {s:?}: contains a NUL byte")))
}

impl SimOptions {
    /// The defaults (`lep_sim_options_init`).
    pub fn new() -> SimOptions {
        let mut raw = sys::lep_sim_options::default();
        // SAFETY: raw is a valid, writable lep_sim_options.
        unsafe { sys::lep_sim_options_init(&mut raw) };
        SimOptions { raw }
    }

    /// Set one option from text, as `leptrino-sim --NAME VALUE` would: the
    /// dash-separated name ("output-rate-field"), the same with underscores,
    /// or the C field name ("rate_hz"); flags take `true`/`false`/`1`/`0`.
    /// An unknown name or a value out of range is `ErrorKind::Arg` with the
    /// library's message, and leaves the options unchanged.
    pub fn set(&mut self, name: &str, value: impl fmt::Display) -> Result<&mut SimOptions> {
        let cname = cstring("option", name)?;
        let cvalue = cstring(name, &value.to_string())?;
        let mut err = [0u8; 256];
        // SAFETY: valid options, NUL-terminated strings, err of the given size.
        let rc = unsafe {
            sys::lep_sim_option_set(
                &mut self.raw,
                cname.as_ptr(),
                cvalue.as_ptr(),
                err.as_mut_ptr().cast::<c_char>(),
                err.len(),
            )
        };
        check_msg(rc, &err, &format!("virtual sensor option {name}"))?;
        Ok(self)
    }

    /// The current value of an option, as text `set` accepts.
    pub fn get(&self, name: &str) -> Result<String> {
        let cname = cstring("option", name)?;
        let mut buf = [0u8; sys::LEP_SIM_PATH_SIZE as usize + 16];
        // SAFETY: valid options and buffer.
        let rc = unsafe {
            sys::lep_sim_option_get(
                &self.raw,
                cname.as_ptr(),
                buf.as_mut_ptr().cast(),
                buf.len(),
            )
        };
        check_msg(rc, &[], &format!("virtual sensor option {name}"))?;
        Ok(crate::error::buf_text(&buf))
    }

    /// Names of every option (dash-separated), from the C table.
    pub fn names() -> Vec<&'static str> {
        // SAFETY: rows and their strings are static data of the library.
        (0..unsafe { sys::lep_sim_option_count() })
            .filter_map(|i| unsafe { sys::lep_sim_option_at(i).as_ref() })
            .map(|row| unsafe { CStr::from_ptr(row.name) }.to_str().unwrap_or(""))
            .collect()
    }
}

/// A virtual sensor owned elsewhere: a [`Simulator`] (through `Deref`), or
/// the one a [`Sensor`](crate::Sensor) opened with
/// [`open_sim`](crate::Sensor::open_sim) runs ([`Sensor::simulator`](crate::Sensor::simulator)).
/// Its calls are thread-safe (sim.h), so it is `Sync`.
#[repr(C)]
pub struct VirtualSensor {
    _opaque: [u8; 0],
    _marker: PhantomData<(*mut u8, PhantomPinned)>,
}

// SAFETY: sim.h: "The functions below are thread-safe."
unsafe impl Send for VirtualSensor {}
// SAFETY: as above; every method takes &self and the C side locks.
unsafe impl Sync for VirtualSensor {}

impl fmt::Debug for VirtualSensor {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("VirtualSensor")
            .field("port", &self.port())
            .finish()
    }
}

impl VirtualSensor {
    /// # Safety
    /// p must be a running lep_sim that outlives 'a.
    pub(crate) unsafe fn from_ptr<'a>(p: *mut sys::lep_sim) -> &'a VirtualSensor {
        &*(p as *const VirtualSensor)
    }

    fn ptr(&self) -> *mut sys::lep_sim {
        self as *const VirtualSensor as *mut sys::lep_sim
    }

    /// The port's path (the link when one was asked for, else the pty).
    pub fn port(&self) -> &str {
        // SAFETY: a static-for-the-life-of-s NUL-terminated path.
        unsafe { CStr::from_ptr(sys::lep_sim_port(self.ptr())) }
            .to_str()
            .unwrap_or("")
    }

    /// Hang up now, as if the USB cable were pulled.
    pub fn hangup(&self) {
        // SAFETY: thread-safe call on a running sim.
        unsafe { sys::lep_sim_hangup(self.ptr()) }
    }

    /// Send nothing and answer nothing for this long, from now.
    pub fn stall(&self, d: Duration) {
        let ms = i32::try_from(d.as_millis()).unwrap_or(i32::MAX);
        // SAFETY: thread-safe call on a running sim.
        unsafe { sys::lep_sim_stall(self.ptr(), ms) }
    }

    /// Switch the virtual power off and on: the stream stops, a pending filter applies.
    pub fn power_cycle(&self) {
        // SAFETY: thread-safe call on a running sim.
        unsafe { sys::lep_sim_power_cycle(self.ptr()) }
    }

    /// What it did so far.
    pub fn stats(&self) -> SimStats {
        let mut st = SimStats::default();
        // SAFETY: thread-safe call on a running sim, valid out pointer.
        unsafe { sys::lep_sim_get_stats(self.ptr(), &mut st) };
        st
    }
}

/// A virtual Leptrino sensor on a pseudo-terminal, served by a C thread of
/// this process until dropped. Any program can open its [`port`](Self::port).
///
/// ```
/// use leptrino::{Sensor, SimOptions, Simulator};
/// let sim = Simulator::start()?;
/// let sensor = Sensor::open(sim.port())?;
/// assert_eq!(sensor.product_info().model, "PFS055YA501U6");
///
/// let mut o = SimOptions::new();
/// o.set("model", "CFS018CA201U")?.set("serial", "12345678")?;
/// let sim = Simulator::start_with(&o)?;
/// assert_eq!(Sensor::open(sim.port())?.product_info().serial, "12345678");
/// # Ok::<(), leptrino::Error>(())
/// ```
pub struct Simulator {
    sim: NonNull<sys::lep_sim>,
}

// SAFETY: sim.h: the functions are thread-safe; lep_sim_stop may be called
// from any thread once (Drop, with no other reference left).
unsafe impl Send for Simulator {}
// SAFETY: see VirtualSensor.
unsafe impl Sync for Simulator {}

impl Simulator {
    /// Start a virtual sensor with the default options.
    pub fn start() -> Result<Simulator> {
        Simulator::start_with(&SimOptions::new())
    }

    /// Start a virtual sensor with these options (checked by the library:
    /// `ErrorKind::Arg` with a message naming the option).
    pub fn start_with(options: &SimOptions) -> Result<Simulator> {
        let mut out: *mut sys::lep_sim = std::ptr::null_mut();
        let mut err = [0u8; 512];
        // SAFETY: valid options (copied by the call), out pointer, err buffer.
        let rc = unsafe {
            sys::lep_sim_start(&options.raw, &mut out, err.as_mut_ptr().cast(), err.len())
        };
        check_msg(rc, &err, "starting the virtual sensor")?;
        let sim = NonNull::new(out)
            .ok_or_else(|| Error::in_context(sys::LEP_E_UNEXPECTED, "lep_sim_start"))?;
        Ok(Simulator { sim })
    }

    /// The port to open: `Sensor::open(sim.port())`.
    pub fn port(&self) -> &str {
        (**self).port()
    }

    /// Names of the model presets.
    pub fn models() -> Vec<String> {
        let mut out = Vec::new();
        // SAFETY: a static NULL-terminated array of static strings.
        unsafe {
            let mut p = sys::lep_sim_models();
            while !(*p).is_null() {
                out.push(CStr::from_ptr(*p).to_string_lossy().into_owned());
                p = p.add(1);
            }
        }
        out
    }

    /// The published rated values of a model preset.
    pub fn model_rated(model: &str) -> Result<Rated> {
        let m = cstring("model", model)?;
        let mut r = sys::lep_rated::default();
        // SAFETY: valid string and out pointer.
        let rc = unsafe { sys::lep_sim_model_rated(m.as_ptr(), &mut r) };
        crate::error::check(rc, &format!("model {model:?}"))?;
        Ok(Rated::from_c(&r))
    }
}

impl std::ops::Deref for Simulator {
    type Target = VirtualSensor;
    fn deref(&self) -> &VirtualSensor {
        // SAFETY: the sim runs until Drop, which needs &mut self.
        unsafe { VirtualSensor::from_ptr(self.sim.as_ptr()) }
    }
}

impl fmt::Debug for Simulator {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Simulator")
            .field("port", &self.port())
            .finish()
    }
}

impl Drop for Simulator {
    fn drop(&mut self) {
        // SAFETY: started by lep_sim_start, stopped once.
        unsafe { sys::lep_sim_stop(self.sim.as_ptr()) }
    }
}
