//! The virtual sensor in-process (leptrino/sim.h): a pseudo-terminal served
//! by a C thread that behaves like a Leptrino sensor, with faults on demand.

use std::ffi::CStr;
use std::fmt;
use std::marker::{PhantomData, PhantomPinned};
use std::ptr::NonNull;
use std::time::Duration;

use leptrino_sys as sys;

use crate::error::{check_msg, Error, Result};
use crate::options::{cstring, static_str, table, Handle};
use crate::Rated;

/// Counters `lep_sim_stats` fills (`LEP_SIMST_*`).
const SIMST_COUNT: usize = sys::LEP_SIMST_COUNT as usize;

/// Counters of what a virtual sensor did since it started (`lep_sim_stats`);
/// [`fields`](Self::fields) gives every counter by the library's names.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SimStats {
    /// Continuous data messages queued to the port.
    pub samples_sent: u64,
    /// Data messages dropped by the drop fault.
    pub samples_dropped: u64,
    /// Commands answered (any result code).
    pub commands: u64,
    /// DLE NAK sent (bad BCC, or the nak fault).
    pub naks: u64,
    /// Messages with a byte flipped by the corrupt fault.
    pub bytes_corrupted: u64,
    /// Hang-ups.
    pub hangups: u64,
    /// Streaming now.
    pub streaming: bool,
    /// Filter code in effect.
    pub filter: u8,
    /// Filter code that takes effect at the next power cycle.
    pub filter_pending: u8,
    /// The pty is closed now (after a hang-up, before a reopen).
    pub hung_up: bool,
    /// Sequence number the next stream sample will carry.
    pub sequence: u16,
    /// Answers to commands queued to the port.
    pub responses: u64,
    /// Of naks: those sent by the nak fault.
    pub faked_naks: u64,
    /// Sample periods with nothing sent: a stall, or late.
    pub samples_skipped: u64,
    /// Data messages not sent because nobody read the port.
    pub samples_blocked: u64,
    /// Bytes added by the garbage fault.
    pub garbage_bytes: u64,
    /// Bytes read from the host.
    pub bytes_received: u64,
    /// New ptys opened after a hang-up.
    pub reopens: u64,
    /// Power cycles applied.
    pub power_cycles: u64,
    /// Stalls begun.
    pub stalls: u64,
    values: [u64; SIMST_COUNT],
}

impl Default for SimStats {
    fn default() -> Self {
        SimStats::from_fields(&[0; SIMST_COUNT])
    }
}

impl SimStats {
    fn from_fields(f: &[u64; SIMST_COUNT]) -> SimStats {
        let n = |i: u32| f[i as usize];
        SimStats {
            samples_sent: n(sys::LEP_SIMST_SAMPLES_SENT),
            samples_dropped: n(sys::LEP_SIMST_SAMPLES_DROPPED),
            commands: n(sys::LEP_SIMST_COMMANDS),
            naks: n(sys::LEP_SIMST_NAKS),
            bytes_corrupted: n(sys::LEP_SIMST_BYTES_CORRUPTED),
            hangups: n(sys::LEP_SIMST_HANGUPS),
            streaming: n(sys::LEP_SIMST_STREAMING) != 0,
            filter: n(sys::LEP_SIMST_FILTER) as u8,
            filter_pending: n(sys::LEP_SIMST_FILTER_PENDING) as u8,
            hung_up: n(sys::LEP_SIMST_HUNG_UP) != 0,
            sequence: n(sys::LEP_SIMST_SEQUENCE) as u16,
            responses: n(sys::LEP_SIMST_RESPONSES),
            faked_naks: n(sys::LEP_SIMST_FAKED_NAKS),
            samples_skipped: n(sys::LEP_SIMST_SAMPLES_SKIPPED),
            samples_blocked: n(sys::LEP_SIMST_SAMPLES_BLOCKED),
            garbage_bytes: n(sys::LEP_SIMST_GARBAGE_BYTES),
            bytes_received: n(sys::LEP_SIMST_BYTES_RECEIVED),
            reopens: n(sys::LEP_SIMST_REOPENS),
            power_cycles: n(sys::LEP_SIMST_POWER_CYCLES),
            stalls: n(sys::LEP_SIMST_STALLS),
            values: *f,
        }
    }

    /// Every counter the library fills, by its name ("samples_sent", ...:
    /// `lep_sim_stats_field_name`), in its order.
    pub fn fields(&self) -> Vec<(&'static str, u64)> {
        // SAFETY: re-entrant; static names, NULL past the end.
        let n = unsafe { sys::lep_sim_stats_fields() }.min(SIMST_COUNT);
        (0..n)
            .map(|i| {
                let name = static_str(unsafe { sys::lep_sim_stats_field_name(i) });
                (name, self.values[i])
            })
            .collect()
    }
}

/// Options of a virtual sensor: those of `leptrino-sim` and of the
/// `leptrino` tool's `--sim-*` options, from the same C table (names,
/// parsing, ranges and defaults are the library's; on an options handle of
/// leptrino/options.h they are the "sim-*" ones).
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
    pub(crate) h: Handle,
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

/// "rate" -> "sim-rate"; "sim-rate" and "sim_rate" as they are.
fn sim_name(name: &str) -> String {
    if name.starts_with("sim-") || name.starts_with("sim_") {
        name.to_owned()
    } else {
        format!("sim-{name}")
    }
}

impl SimOptions {
    /// The defaults.
    pub fn new() -> SimOptions {
        SimOptions { h: Handle::new() }
    }

    /// Set one option from text, as `leptrino-sim --NAME VALUE` would: the
    /// dash-separated name ("output-rate-field"), the same with underscores,
    /// or either with the "sim-" prefix of the options handle; flags take
    /// `true`/`false`/`1`/`0`. An unknown name or a value out of range is
    /// `ErrorKind::Arg` with the library's message, and leaves the options
    /// unchanged.
    pub fn set(&mut self, name: &str, value: impl fmt::Display) -> Result<&mut SimOptions> {
        self.h.set_text(&sim_name(name), &value.to_string())?;
        Ok(self)
    }

    /// The current value of an option, as text `set` accepts.
    pub fn get(&self, name: &str) -> Result<String> {
        self.h.get_text(&sim_name(name))
    }

    /// Names of every option (dash-separated, without "sim-"), from the C table.
    pub fn names() -> Vec<&'static str> {
        table()
            .filter(|&(_, _, scope)| scope == sys::LEP_SCOPE_SIM as i32)
            .map(|(_, name, _)| name.strip_prefix("sim-").unwrap_or(name))
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

    /// Hold the output for this long from now (zero: release now): samples
    /// are made at their times and queued, then written together when the
    /// hold ends, as from a sender or a USB adapter running late.
    pub fn hold(&self, d: Duration) {
        let ms = i32::try_from(d.as_millis()).unwrap_or(i32::MAX);
        // SAFETY: thread-safe call on a running sim.
        unsafe { sys::lep_sim_hold(self.ptr(), ms) }
    }

    /// What it did so far.
    pub fn stats(&self) -> SimStats {
        let mut st = [0u64; SIMST_COUNT];
        // SAFETY: thread-safe call on a running sim; SIMST_COUNT counters.
        unsafe { sys::lep_sim_stats(self.ptr(), st.as_mut_ptr(), SIMST_COUNT) };
        SimStats::from_fields(&st)
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
        let rc = options.h.with(|o| unsafe {
            sys::lep_sim_start(o, &mut out, err.as_mut_ptr().cast(), err.len())
        });
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
        // SAFETY: re-entrant; static names, NULL past the end.
        (0..unsafe { sys::lep_sim_model_count() })
            .map(|i| static_str(unsafe { sys::lep_sim_model_name(i) }).to_owned())
            .collect()
    }

    /// The published rated values of a model preset.
    pub fn model_rated(model: &str) -> Result<Rated> {
        let m = cstring("model", model)?;
        let mut r = [0.0; 6];
        // SAFETY: valid string, 6 doubles.
        let rc = unsafe { sys::lep_sim_model_rated(m.as_ptr(), r.as_mut_ptr()) };
        crate::error::check(rc, &format!("model {model:?}"))?;
        Ok(Rated::from_axes(r))
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
