//! A sensor through the library's host session (leptrino/session.h).
//!
//! Everything the session does (start-up recovery, tare, host low-pass,
//! decimation, rotation, gap detection, reconnect, health, metadata) runs in
//! C; this module reads its samples (`lep_session_read`) straight into plain
//! vectors and its events, health and metadata (arrays of numbers indexed by
//! the header's enumerators, texts by `lep_session_info`) into Rust values.

use std::cell::Cell;
use std::ffi::{c_char, CStr};
use std::fmt;
use std::marker::PhantomData;
use std::ptr::NonNull;
use std::sync::Arc;
use std::time::Duration;

use leptrino_sys as sys;

use crate::error::{check, check_msg, text_result, Error, Result};
use crate::options::{cstring, Handle, Options};
use crate::sim::{SimOptions, VirtualSensor};
use crate::values::{
    Event, Health, MetaNumbers, Metadata, Payload, ProductInfo, Rated, Recording, Sample,
    EVF_COUNT, H_COUNT, MD_COUNT,
};

/// Samples per `lep_session_read` of the sample iterator.
const ITER_BATCH: usize = 256;
/// Longest wait of one `lep_session_read` in record().
const RECORD_SLICE_S: f64 = 0.25;
/// record() returns only at its end, so it lets the library hold samples back
/// this long (ms) to save wake-ups; the sensor's own budget comes back after.
const RECORD_LATENCY_MS: i64 = 100;
/// Reads after the end of record(duration) that collect what the budget held back.
const RECORD_FINAL_READS: u32 = 64;
/// Room for the one-line messages of lep_session_open and lep_session_set*.
const ERR_LEN: usize = 512;

fn monotonic() -> f64 {
    // SAFETY: no arguments, no state.
    unsafe { sys::lep_monotonic_seconds() }
}

/// The session pointer, shared by a [`Sensor`] and its [`Control`]s; closed
/// when the last of them goes.
struct Session(NonNull<sys::lep_session>);

// SAFETY: session.h: the driving calls (start, read, read_one, stop, the
// "latency" option) are for one thread at a time: only Sensor makes them
// (and uses the session's client), and Sensor is not Sync. The calls Control
// makes (tare, untare, set/get tare, taring, lep_session_set*/get* of the
// other live options, health, metadata, rated, info, next_event) "may be
// called from any thread at any time before close".
unsafe impl Send for Session {}
// SAFETY: see above.
unsafe impl Sync for Session {}

impl Drop for Session {
    fn drop(&mut self) {
        // SAFETY: opened by lep_session_open, closed once, nobody else holds it.
        unsafe { sys::lep_session_close(self.0.as_ptr()) }
    }
}

/// The calls of a session that any thread may make at any time, without
/// blocking on I/O (a mutex inside the session): tare, untare, the tare
/// offsets, the low-pass, the output frame, health and metadata.
///
/// A [`Sensor`] derefs to its `Control`; [`Sensor::control`] gives a clone to
/// hand to another thread (`Send + Sync`). The session stays open until the
/// sensor and every clone are dropped.
///
/// ```
/// let mut sensor = leptrino::Sensor::open_sim(&leptrino::SimOptions::new(),
///                                             &leptrino::Options::new())?;
/// let control = sensor.control();
/// std::thread::scope(|s| {
///     s.spawn(|| control.begin_tare(50).unwrap());
/// });
/// let rec = sensor.record_count(200)?;
/// assert!(rec.events.iter().any(|e| matches!(e.kind, leptrino::EventKind::Tare { .. })));
/// # Ok::<(), leptrino::Error>(())
/// ```
#[derive(Clone)]
pub struct Control {
    session: Arc<Session>,
    port: Arc<str>,
}

impl fmt::Debug for Control {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Control").field("port", &self.port).finish()
    }
}

impl Control {
    fn ptr(&self) -> *mut sys::lep_session {
        self.session.0.as_ptr()
    }

    /// Begin a tare over the next n samples (the stream goes on; the samples
    /// it averages carry the taring flag); a `Tare` event marks its end.
    /// Replaces a tare in progress. Before the stream starts, it begins with it.
    pub fn begin_tare(&self, n: u32) -> Result<()> {
        let n = i32::try_from(n).unwrap_or(i32::MAX);
        // SAFETY: any-thread call on an open session.
        check(
            unsafe { sys::lep_session_tare(self.ptr(), n, 0.0) },
            &format!("{}: tare", self.port),
        )
    }

    /// Remove the tare (offsets zero); cancels a tare in progress.
    pub fn untare(&self) -> Result<()> {
        // SAFETY: any-thread call on an open session.
        check(
            unsafe { sys::lep_session_untare(self.ptr()) },
            &format!("{}: untare", self.port),
        )
    }

    /// The tare offsets in force, counts (zeros when not tared).
    pub fn tare_offsets(&self) -> [f64; 6] {
        let mut off = [0.0; 6];
        // SAFETY: any-thread call; off holds 6 doubles.
        unsafe { sys::lep_session_get_tare(self.ptr(), off.as_mut_ptr()) };
        off
    }

    /// Set the tare offsets, counts.
    pub fn set_tare_offsets(&self, counts: [f64; 6]) -> Result<()> {
        // SAFETY: any-thread call; counts holds 6 doubles.
        let rc = unsafe { sys::lep_session_set_tare(self.ptr(), counts.as_ptr()) };
        check(rc, &format!("{}: tare offsets", self.port))
    }

    /// True while a tare is in force.
    pub fn tared(&self) -> bool {
        // SAFETY: any-thread call; NULL offsets are allowed.
        unsafe { sys::lep_session_get_tare(self.ptr(), std::ptr::null_mut()) == 1 }
    }

    /// Change an option of the open session by name, from text, as
    /// `lep_session_set` (the options of scope "live": "lowpass",
    /// "rotation", "shift", "payload", "gravity", "limit"; "latency" is the
    /// reading thread's and is refused here). Another option is
    /// `ErrorKind::State`; a bad value `ErrorKind::Arg` or `ErrorKind::Value`,
    /// with the library's message naming it.
    ///
    /// ```
    /// let s = leptrino::Sensor::open_sim(&Default::default(), &Default::default())?;
    /// s.set("lowpass", 100)?;
    /// assert_eq!(s.lowpass(), 100.0);
    /// assert_eq!(s.set("decimate", 2).unwrap_err().kind(), leptrino::ErrorKind::State);
    /// # Ok::<(), leptrino::Error>(())
    /// ```
    pub fn set(&self, name: &str, value: impl fmt::Display) -> Result<()> {
        if name == "latency" {
            return Err(Error::with_message(
                sys::LEP_E_STATE,
                format!(
                    "{}: latency: set it on the Sensor (the reading thread)",
                    self.port
                ),
            ));
        }
        let v = cstring(name, &value.to_string())?;
        self.set_with(name, |s, n, e, l| unsafe {
            sys::lep_session_set(s, n, v.as_ptr(), e, l)
        })
    }

    fn set_with(
        &self,
        name: &str,
        f: impl FnOnce(*mut sys::lep_session, *const c_char, *mut c_char, usize) -> i32,
    ) -> Result<()> {
        let cname = cstring("option", name)?;
        let mut err = [0u8; ERR_LEN];
        // f makes an any-thread call on an open session with these buffers.
        let rc = f(
            self.ptr(),
            cname.as_ptr(),
            err.as_mut_ptr().cast(),
            err.len(),
        );
        check_msg(rc, &err, &format!("{}: {name}", self.port))
    }

    fn set_doubles(&self, name: &str, v: &[f64]) -> Result<()> {
        // SAFETY: any-thread call; v holds v.len() doubles.
        self.set_with(name, |s, n, e, l| unsafe {
            sys::lep_session_set_doubles(s, n, v.as_ptr(), v.len(), e, l)
        })
    }

    /// Any option as the session uses it now, as text (the live ones as last
    /// set; "port" the path opened).
    pub fn get(&self, name: &str) -> Result<String> {
        let cname = cstring("option", name)?;
        // SAFETY: any-thread call; buf holds cap bytes (or is NULL with cap 0).
        text_result(
            |buf, cap, len| unsafe {
                sys::lep_session_get(self.ptr(), cname.as_ptr(), buf, cap, len)
            },
            &format!("{}: option {name:?}", self.port),
        )
    }

    fn get_doubles<const N: usize>(&self, cname: &CStr) -> [f64; N] {
        let mut v = [0.0; N];
        // SAFETY: any-thread call; v holds N doubles.
        unsafe {
            sys::lep_session_get_doubles(
                self.ptr(),
                cname.as_ptr(),
                v.as_mut_ptr(),
                N,
                std::ptr::null_mut(),
            )
        };
        v
    }

    /// The host low-pass cut-off in force, Hz (0 off).
    pub fn lowpass(&self) -> f64 {
        let mut hz = 0.0;
        // SAFETY: any-thread call, valid out pointer.
        unsafe { sys::lep_session_get_double(self.ptr(), c"lowpass".as_ptr(), &mut hz) };
        hz
    }

    /// Change the host low-pass cut-off, Hz (0 off; `ErrorKind::Value` above
    /// 0.45 x the rate).
    pub fn set_lowpass(&self, hz: f64) -> Result<()> {
        // SAFETY: any-thread call.
        self.set_with("lowpass", |s, n, e, l| unsafe {
            sys::lep_session_set_double(s, n, hz, e, l)
        })
    }

    /// The output frame in force: rotation (row-major) and moment point (m).
    pub fn frame(&self) -> ([f64; 9], [f64; 3]) {
        (self.get_doubles(c"rotation"), self.get_doubles(c"shift"))
    }

    /// Change the output frame (rotation row-major, moment point in metres);
    /// `ErrorKind::Value` for a matrix that is not orthonormal. On an error
    /// the frame is unchanged.
    pub fn set_frame(&self, rotation: [f64; 9], shift_m: [f64; 3]) -> Result<()> {
        let (old_rotation, _) = self.frame();
        self.set_doubles("rotation", &rotation)?;
        if let Err(e) = self.set_doubles("shift", &shift_m) {
            let _ = self.set_doubles("rotation", &old_rotation);
            return Err(e);
        }
        Ok(())
    }

    /// Limits on the SI values, per axis (N, N·m; 0: none): a sample beyond
    /// one is flagged and `LimitExceeded` / `LimitCleared` events mark the
    /// episodes. `ErrorKind::Arg` for negative or non-finite limits.
    pub fn set_limits(&self, limits: [f64; 6]) -> Result<()> {
        self.set_doubles("limit", &limits)
    }

    /// The limits in force (0: none).
    pub fn limits(&self) -> [f64; 6] {
        self.get_doubles(c"limit")
    }

    /// Remove a tool's gravity wrench from the SI values (raw and zeroed
    /// counts stay as measured), `None` for none. A tare taken while a
    /// payload is set removes the bias only. `ErrorKind::Arg` for a negative
    /// mass or non-finite values. Applies from the next sample.
    ///
    /// ```
    /// use leptrino::{Options, Payload, Sensor, SimOptions};
    /// let mut sim = SimOptions::new();
    /// sim.set("payload", "0.5,0,0,0.05")?.set("noise", 0)?;
    /// let mut s = Sensor::open_sim(&sim, &Options::new())?;
    /// s.set_payload(Some(Payload::new(0.5, [0.0, 0.0, 0.05])))?;
    /// assert_eq!(s.payload(), Some(Payload::new(0.5, [0.0, 0.0, 0.05])));
    /// # Ok::<(), leptrino::Error>(())
    /// ```
    pub fn set_payload(&self, payload: Option<Payload>) -> Result<()> {
        self.set_doubles("payload", &payload.unwrap_or_default().to_array())
    }

    /// The payload compensated, if any.
    pub fn payload(&self) -> Option<Payload> {
        Payload::from_array(self.get_doubles(c"payload"))
    }

    /// Gravity in the sensor frame, m/s² ((0, 0, -9.80665) when its z axis
    /// points up): what payload compensation uses. Set it as often as the
    /// robot moves.
    pub fn set_gravity(&self, gravity: [f64; 3]) -> Result<()> {
        self.set_doubles("gravity", &gravity)
    }

    /// Gravity in force, m/s², sensor frame.
    pub fn gravity(&self) -> [f64; 3] {
        self.get_doubles(c"gravity")
    }

    /// Health since the stream started.
    pub fn health(&self) -> Health {
        let mut h = [0.0; H_COUNT];
        // SAFETY: any-thread call; H_COUNT doubles.
        unsafe { sys::lep_session_health(self.ptr(), h.as_mut_ptr(), H_COUNT) };
        Health::from_fields(&h)
    }

    fn numbers(&self) -> MetaNumbers {
        let mut m = [0.0; MD_COUNT];
        // SAFETY: any-thread call; MD_COUNT doubles.
        unsafe { sys::lep_session_metadata(self.ptr(), m.as_mut_ptr(), MD_COUNT) };
        MetaNumbers(m)
    }

    /// A text of `lep_session_info` (`LEP_INFO_*`).
    fn info(&self, which: u32) -> Result<String> {
        // SAFETY: any-thread call; buf holds cap bytes (or is NULL with cap 0).
        text_result(
            |buf, cap, len| unsafe {
                sys::lep_session_info(self.ptr(), which as i32, buf, cap, len)
            },
            &format!("{}: session info", self.port),
        )
    }

    fn product_info(&self, m: &MetaNumbers) -> ProductInfo {
        ProductInfo {
            model: self.info(sys::LEP_INFO_MODEL).unwrap_or_default(),
            serial: self.info(sys::LEP_INFO_SERIAL).unwrap_or_default(),
            firmware: self.info(sys::LEP_INFO_FIRMWARE).unwrap_or_default(),
            output_rate_hz: m.output_rate_hz(),
        }
    }

    /// The sensor's digital filter code as read when it was opened (0 off,
    /// 1..3); `None` when the sensor refused or did not answer. A new code
    /// ([`Sensor::set_filter`]) applies after a power cycle.
    pub fn filter(&self) -> Option<u8> {
        self.numbers().sensor_filter()
    }

    /// The label of that filter code ("10 Hz", ...), or "not supported by sensor".
    pub fn filter_label(&self) -> String {
        self.info(sys::LEP_INFO_FILTER_LABEL).unwrap_or_default()
    }

    /// What the session says about itself: identity, rated values, filters,
    /// tare, frame, payload, limits, start time.
    pub fn metadata(&self) -> Metadata {
        let m = self.numbers();
        let text = |which| self.info(which).unwrap_or_default();
        Metadata {
            product: self.product_info(&m),
            protocol: text(sys::LEP_INFO_PROTOCOL),
            rated: m.rated(),
            sensor_filter: m.sensor_filter(),
            sensor_filter_label: text(sys::LEP_INFO_FILTER_LABEL),
            nominal_hz: m.nominal_hz(),
            lowpass_hz: m.at(sys::LEP_MD_LOWPASS_HZ),
            lowpass_name: text(sys::LEP_INFO_LOWPASS_NAME),
            lowpass_delay_s: m.at(sys::LEP_MD_LOWPASS_DELAY_S),
            decimate: m.at(sys::LEP_MD_DECIMATE) as u32,
            rotation: m.rotation(),
            shift_m: crate::values::three(&m.0, sys::LEP_MD_SHIFT_M),
            tared: m.at(sys::LEP_MD_TARED) != 0.0,
            tare: crate::values::six(&m.0, sys::LEP_MD_TARE),
            start_utc: m.at(sys::LEP_MD_START_UTC),
            start_mono: m.start_mono(),
            port: text(sys::LEP_INFO_PORT),
            sim: m.at(sys::LEP_MD_SIM) != 0.0,
            library_version: text(sys::LEP_INFO_LIBRARY_VERSION),
            payload: m.payload(),
            gravity: crate::values::three(&m.0, sys::LEP_MD_GRAVITY),
            limit: crate::values::six(&m.0, sys::LEP_MD_LIMIT),
        }
    }

    /// The metadata as the library writes it in every recording: one JSON
    /// object (model, serial, firmware, rated values, filters, tare, frame,
    /// start time, library version).
    pub fn metadata_json(&self) -> Result<String> {
        self.info(sys::LEP_INFO_METADATA_JSON)
    }
}

/// A Leptrino sensor, through the library's session.
///
/// Opening takes the port exclusively and recovers from whatever state the
/// sensor was left in (stops a running stream, drains, identifies), then
/// reads the rated values and the filter. Dropping it stops a running stream
/// and releases the port (once every [`Control`] clone is gone too).
///
/// `Send` but not `Sync`: one thread drives a session at a time (session.h);
/// the calls other threads may make go through [`Control`].
///
/// ```compile_fail
/// fn sync<T: Sync>() {}
/// sync::<leptrino::Sensor>(); // two threads may not drive one session
/// ```
///
/// ```
/// use std::time::Duration;
/// use leptrino::{Sensor, Simulator};
/// let sim = Simulator::start()?;
/// let mut sensor = Sensor::open(sim.port())?;
/// println!("{} #{} firmware {}", sensor.product_info().model,
///          sensor.product_info().serial, sensor.product_info().firmware);
/// println!("rated force {:?} N, torque {:?} N m", sensor.rated().force, sensor.rated().torque);
/// let rec = sensor.record(Duration::from_millis(100))?;
/// println!("{} samples, Fz of the first {:.3} N", rec.len(), rec.force(0)[2]);
/// # assert!(rec.len() > 60);
/// # Ok::<(), leptrino::Error>(())
/// ```
pub struct Sensor {
    control: Control,
    info: ProductInfo,
    rated: Rated,
    nominal_hz: f64,
    decimate: u32,
    timeout_ms: i32,
    events: Vec<Event>,
    _not_sync: PhantomData<Cell<()>>,
}

impl fmt::Debug for Sensor {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Sensor")
            .field("port", &self.port())
            .field("info", &self.info)
            .field("rated", &self.rated)
            .finish_non_exhaustive()
    }
}

impl std::ops::Deref for Sensor {
    type Target = Control;
    fn deref(&self) -> &Control {
        &self.control
    }
}

impl Sensor {
    /// Open the sensor on a serial port (or a [`Simulator`](crate::Simulator)'s
    /// port) with the default options.
    pub fn open(port: &str) -> Result<Sensor> {
        Sensor::open_with(port, &Options::new())
    }

    /// Open the sensor on a port with these options.
    pub fn open_with(port: &str, options: &Options) -> Result<Sensor> {
        let mut h = Sensor::handle(options)?;
        h.set_int("sim", 0)?;
        h.set_text("port", port)?;
        Sensor::open_handle(&h, port)
    }

    /// Open a virtual sensor that the session starts itself (and stops when
    /// closed); [`simulator`](Self::simulator) reaches it for fault injection.
    /// Its options are `sim`'s (every "sim-*" of `options` is replaced).
    pub fn open_sim(sim: &SimOptions, options: &Options) -> Result<Sensor> {
        let mut h = Sensor::handle(options)?;
        h.set_int("sim", 1)?;
        for (_, name, scope) in crate::options::table() {
            if scope == sys::LEP_SCOPE_SIM as i32 {
                let v = sim.h.get_text(name)?;
                if h.get_text(name)? != v {
                    h.set_text(name, &v)?;
                }
            }
        }
        Sensor::open_handle(&h, "virtual sensor")
    }

    fn handle(options: &Options) -> Result<Handle> {
        match options.deferred_error() {
            Some(e) => Err(e),
            None => Ok(options.h.clone()),
        }
    }

    fn open_handle(h: &Handle, what: &str) -> Result<Sensor> {
        let mut out: *mut sys::lep_session = std::ptr::null_mut();
        let mut err = [0u8; ERR_LEN];
        // SAFETY: a live options handle (copied by the call), out pointer,
        // err buffer of its size.
        let rc = h.with(|o| unsafe {
            sys::lep_session_open(o, &mut out, err.as_mut_ptr().cast(), err.len())
        });
        check_msg(rc, &err, what)?;
        let session = Session(
            NonNull::new(out).ok_or_else(|| Error::in_context(sys::LEP_E_UNEXPECTED, what))?,
        );
        // SAFETY: the port's path, NUL-terminated, valid while the session is.
        let port: Arc<str> = unsafe { CStr::from_ptr(sys::lep_session_port(session.0.as_ptr())) }
            .to_string_lossy()
            .into();
        let control = Control {
            session: Arc::new(session),
            port,
        };
        let meta = control.numbers();
        let int = |name: &CStr| {
            let mut v = 0i64;
            // SAFETY: any-thread call, valid out pointer.
            unsafe { sys::lep_session_get_int(control.ptr(), name.as_ptr(), &mut v) };
            v
        };
        let nominal = meta.nominal_hz();
        Ok(Sensor {
            info: control.product_info(&meta),
            rated: meta.rated(),
            nominal_hz: if nominal > 0.0 {
                nominal
            } else {
                f64::from(sys::LEP_SESSION_NOMINAL_HZ)
            },
            decimate: u32::try_from(int(c"decimate")).unwrap_or(1).max(1),
            timeout_ms: i32::try_from(int(c"timeout")).unwrap_or(500).max(1),
            control,
            events: Vec::new(),
            _not_sync: PhantomData,
        })
    }

    fn ptr(&self) -> *mut sys::lep_session {
        self.control.ptr()
    }

    /// The port's path.
    pub fn port(&self) -> &str {
        &self.control.port
    }

    /// What the sensor said it is when it was opened.
    pub fn product_info(&self) -> &ProductInfo {
        &self.info
    }

    /// Its rated values, read when it was opened.
    pub fn rated(&self) -> Rated {
        self.rated
    }

    /// A handle for the calls any thread may make (tare, untare, low-pass,
    /// frame, health, metadata); `Send + Sync`.
    pub fn control(&self) -> Control {
        self.control.clone()
    }

    /// The virtual sensor the session runs ([`open_sim`](Self::open_sim)), for
    /// fault injection; `None` on a port.
    pub fn simulator(&self) -> Option<&VirtualSensor> {
        // SAFETY: the session's sim lives as long as the session, which
        // outlives &self.
        unsafe {
            let p = sys::lep_session_sim(self.ptr());
            (!p.is_null()).then(|| VirtualSensor::from_ptr(p))
        }
    }

    /// Events the sensor's own waits (tare) read, since the last call.
    pub fn take_events(&mut self) -> Vec<Event> {
        std::mem::take(&mut self.events)
    }

    /// True while the stream runs.
    pub fn streaming(&self) -> bool {
        // SAFETY: driving-thread call (Sensor is not Sync).
        unsafe { sys::lep_session_streaming(self.ptr()) == 1 }
    }

    /// Set the sensor's digital filter (0 off, 1..3: per spec v1.13 10, 100,
    /// 200 Hz; models differ, the code is the truth), as `leptrino filter`
    /// does: the sensor stores it and applies it only after its power is
    /// switched off and on. [`filter`](Control::filter) keeps saying the code
    /// read at open. `ErrorKind::Value` for a code above 3, `ErrorKind::State`
    /// while streaming, `ErrorKind::Sensor` when the sensor refuses (with its
    /// result code).
    ///
    /// ```
    /// use leptrino::{Sensor, Simulator};
    /// let sim = Simulator::start()?;
    /// let mut s = Sensor::open(sim.port())?;
    /// assert_eq!(s.filter(), Some(0));
    /// s.set_filter(2)?;
    /// assert_eq!(sim.stats().filter_pending, 2);
    /// drop(s);
    /// sim.power_cycle(); // done by the virtual sensor's thread
    /// # while sim.stats().filter != 2 { std::thread::sleep(std::time::Duration::from_millis(5)); }
    /// let s = Sensor::open(sim.port())?;
    /// assert_eq!((s.filter(), s.filter_label().as_str()), (Some(2), "100 Hz"));
    /// # Ok::<(), leptrino::Error>(())
    /// ```
    pub fn set_filter(&mut self, code: u8) -> Result<()> {
        if self.streaming() {
            return Err(Error::with_message(
                sys::LEP_E_STATE,
                format!("{}: filter set: stop the stream first", self.port()),
            ));
        }
        // SAFETY: a driving-thread call (Sensor is not Sync); the client is
        // the session's, an opaque pointer passed back to the library.
        let c = unsafe { sys::lep_session_client(self.ptr()) };
        if c.is_null() {
            return Err(Error::in_context(
                sys::LEP_E_DISCONNECTED,
                &format!("{}: filter set", self.port()),
            ));
        }
        // SAFETY: as above; the session is not streaming, nobody else drives it.
        let rc = unsafe { sys::lep_client_filter_set(c, code) };
        self.check_cmd(rc, "filter set")
    }

    /// The latency budget in force ([`Options::latency`]).
    pub fn latency(&self) -> Duration {
        let mut v = 0i64;
        // SAFETY: valid out pointer.
        unsafe { sys::lep_session_get_int(self.ptr(), c"latency".as_ptr(), &mut v) };
        Duration::from_millis(u64::try_from(v).unwrap_or(0))
    }

    /// Change the latency budget (the reading thread's option).
    pub fn set_latency(&mut self, d: Duration) -> Result<()> {
        let ms = crate::options::ms(d);
        // SAFETY: a driving-thread call.
        self.control.set_with("latency", |s, n, e, l| unsafe {
            sys::lep_session_set_int(s, n, ms, e, l)
        })
    }

    fn latency_ms(&self) -> i64 {
        i64::try_from(self.latency().as_millis()).unwrap_or(i64::MAX)
    }

    fn set_latency_ms(&mut self, ms: i64) {
        // SAFETY: a driving-thread call.
        let _ = self.control.set_with("latency", |s, n, e, l| unsafe {
            sys::lep_session_set_int(s, n, ms, e, l)
        });
    }

    /// An error from a command, with the sensor's result code when it refused.
    fn cmd_error(&self, rc: i32, what: &str) -> Error {
        let e = Error::in_context(rc, &format!("{}: {what}", self.port()));
        if rc == sys::LEP_E_SENSOR {
            // SAFETY: driving-thread calls; the client may be NULL while disconnected.
            let c = unsafe { sys::lep_session_client(self.ptr()) };
            if !c.is_null() {
                return e.set_sensor_result(unsafe { sys::lep_client_last_result(c) });
            }
        }
        e
    }

    fn check_cmd(&self, rc: i32, what: &str) -> Result<()> {
        if rc < 0 {
            Err(self.cmd_error(rc, what))
        } else {
            Ok(())
        }
    }

    /// Start the stream (record(), stream() and tare() start it themselves
    /// when it is not running, and stop it again after).
    pub fn start(&mut self) -> Result<()> {
        // SAFETY: driving-thread call.
        let rc = unsafe { sys::lep_session_start(self.ptr()) };
        self.check_cmd(rc, "starting the stream")
    }

    /// Stop the stream; samples received and not yet read are dropped.
    pub fn stop(&mut self) -> Result<()> {
        // SAFETY: driving-thread call.
        let rc = unsafe { sys::lep_session_stop(self.ptr()) };
        self.check_cmd(rc, "stopping the stream")
    }

    /// One sample in handshake mode (command 0x30), outside the stream,
    /// through the session (`lep_session_read_one`): zeroed and SI values with
    /// the tare, rotation and moment-point shift in force (the host low-pass
    /// and decimation are the stream's and do not apply). `ErrorKind::State`
    /// while streaming.
    ///
    /// ```
    /// let mut s = leptrino::Sensor::open_sim(&leptrino::SimOptions::new(), &Default::default())?;
    /// let x = s.read()?;
    /// assert!((x.si[2] - f64::from(x.raw[2]) * s.rated().force[2] / 10000.0).abs() < 1e-9);
    /// # Ok::<(), leptrino::Error>(())
    /// ```
    pub fn read(&mut self) -> Result<Sample> {
        let mut one = Recording::with_capacity(1);
        let s = self.ptr();
        let (rc, _) = append(&mut one, 1, |c, n| {
            // SAFETY: driving-thread call; every column has room for one row.
            let rc = unsafe {
                sys::lep_session_read_one(
                    s, c.t_mono, c.t_utc, c.si, c.raw, c.zeroed, c.status, c.flags, c.seq,
                )
            };
            *n = usize::from(rc == sys::LEP_OK);
            rc
        });
        self.check_cmd(rc, "reading a sample")?;
        if one.is_empty() {
            return Err(Error::in_context(
                sys::LEP_E_UNEXPECTED,
                &format!("{}: reading a sample", self.port()),
            ));
        }
        Ok(one.sample(0))
    }

    /// Tare: zero on the mean raw counts of the next n samples, and return
    /// the offsets (counts). Starts the stream when it is not running, waits
    /// for the tare to finish and stops it again; in a running stream it
    /// waits there (the samples it reads are not kept; their events are, in
    /// [`take_events`](Self::take_events)). To tare beside a stream you read,
    /// use [`Stream::begin_tare`] or [`Control::begin_tare`].
    ///
    /// ```
    /// let mut o = leptrino::SimOptions::new();
    /// o.set("constant", true)?.set("amplitude", 0.1)?;
    /// let mut s = leptrino::Sensor::open_sim(&o, &Default::default())?;
    /// assert_eq!(s.tare(50)?, [1000.0; 6]);
    /// s.untare()?;
    /// assert!(!s.tared());
    /// # Ok::<(), leptrino::Error>(())
    /// ```
    pub fn tare(&mut self, n: u32) -> Result<[f64; 6]> {
        if n == 0 {
            return Err(Error::arg(format!("{}: tare over 0 samples", self.port())));
        }
        self.control.begin_tare(n)?;
        let started = !self.streaming();
        if started {
            self.start()?;
        }
        let result = self.wait_tare();
        if started {
            let _ = self.stop();
        }
        result.map(|()| self.control.tare_offsets())
    }

    fn wait_tare(&mut self) -> Result<()> {
        let mut scratch = Recording::with_capacity(ITER_BATCH);
        // SAFETY (each call): driving-thread calls on an open session.
        while unsafe { sys::lep_session_taring(self.ptr()) } == 1 {
            scratch.clear_rows();
            let (rc, _) = read_into(self.ptr(), &mut scratch, ITER_BATCH, self.timeout_ms);
            let mut new = self.drain_events(None);
            self.events.append(&mut new);
            if rc < 0 && rc != sys::LEP_E_END {
                return Err(self.cmd_error(rc, "tare"));
            }
        }
        Ok(())
    }

    /// The queued events (`Event::from_fields` says what `first` does).
    fn drain_events(&mut self, first: Option<u64>) -> Vec<Event> {
        let mut out = Vec::new();
        let mut ev = [0.0; EVF_COUNT];
        // SAFETY: any-thread call; ev holds EVF_COUNT doubles.
        while unsafe { sys::lep_session_next_event(self.ptr(), ev.as_mut_ptr(), EVF_COUNT) } == 1 {
            out.push(Event::from_fields(&ev, first));
        }
        out
    }

    /// Record the stream for this long (from the first row's arrival, as
    /// `leptrino stream --duration` counts), into plain vectors. Starts the
    /// stream when it is not running and stops it again after. An error
    /// (the port gone: `Disconnected`; no data for the data timeout: `Lost`)
    /// carries what was recorded until then: [`Error::recording`].
    ///
    /// ```
    /// use std::time::Duration;
    /// let mut s = leptrino::Sensor::open_sim(&leptrino::SimOptions::new(), &Default::default())?;
    /// let rec = s.record(Duration::from_millis(250))?;
    /// assert!((250..=350).contains(&rec.len()) && rec.missing() == 0);
    /// # Ok::<(), leptrino::Error>(())
    /// ```
    pub fn record(&mut self, duration: Duration) -> Result<Recording> {
        if duration.is_zero() {
            return Err(Error::arg(format!(
                "{}: record for a zero duration",
                self.port()
            )));
        }
        self.record_until(Some(duration.as_secs_f64()), None)
    }

    /// Record exactly `count` samples of the stream (as [`record`](Self::record)).
    pub fn record_count(&mut self, count: usize) -> Result<Recording> {
        if count == 0 {
            return Err(Error::arg(format!("{}: record 0 samples", self.port())));
        }
        self.record_until(None, Some(count))
    }

    fn record_until(&mut self, seconds: Option<f64>, count: Option<usize>) -> Result<Recording> {
        let rate = self.nominal_hz / f64::from(self.decimate);
        let cap = match (count, seconds) {
            (Some(c), _) => c,
            (None, Some(s)) => (s * rate * 1.05) as usize + 64,
            (None, None) => unreachable!(),
        };
        let mut rec = Recording::with_capacity(cap);
        let started = !self.streaming();
        if started {
            self.start()?;
        }
        let latency_before = self.latency_ms();
        if latency_before < RECORD_LATENCY_MS {
            self.set_latency_ms(RECORD_LATENCY_MS);
        }
        let result = self.record_loop(&mut rec, seconds, count, rate);
        self.set_latency_ms(latency_before);
        if started {
            let _ = self.stop();
        }
        rec.metadata_json = self.control.metadata_json().unwrap_or_default();
        match result {
            Ok(()) => Ok(rec),
            Err(e) => Err(e.set_recording(rec)),
        }
    }

    fn record_loop(
        &mut self,
        rec: &mut Recording,
        seconds: Option<f64>,
        count: Option<usize>,
        rate: f64,
    ) -> Result<()> {
        let timeout_s = f64::from(self.timeout_ms) / 1000.0;
        let mut now = monotonic();
        let mut end = f64::INFINITY;
        let mut final_reads = 0;
        loop {
            let n = rec.len();
            let (room, wait_s) = if let Some(c) = count {
                if n >= c {
                    return Ok(());
                }
                (c - n, RECORD_SLICE_S.min(timeout_s))
            } else {
                let s = seconds.unwrap_or(0.0);
                let left = if n > 0 { end - now } else { s };
                if left <= 0.0 {
                    // Time is up, but the latency budget may still hold samples
                    // that arrived before the end: take them with reads that do
                    // not wait, up to the first one after it.
                    if n > 0 && rec.t[n - 1] >= end || final_reads >= RECORD_FINAL_READS {
                        return Ok(());
                    }
                    if final_reads == 0 {
                        self.set_latency_ms(0);
                    }
                    final_reads += 1;
                }
                let room = ((left.max(0.0) * rate).ceil() as usize).max(64);
                (room, RECORD_SLICE_S.min(left.max(0.001)).min(timeout_s))
            };
            let wait_ms = ((wait_s * 1000.0) as i32).max(1);
            let (rc, added) = read_into(self.ptr(), rec, room, wait_ms);
            if let (Some(s), 0) = (seconds, n) {
                if added > 0 {
                    end = rec.t[0] + s;
                }
            }
            let mut new = self.drain_events(Some(n as u64)); // rows of the recording
            rec.events.append(&mut new);
            now = monotonic();
            if rc == sys::LEP_E_END {
                return Ok(());
            }
            if rc == sys::LEP_E_TIMEOUT {
                continue; // nothing in this slice of the wait (a lost stream is LEP_E_LOST)
            }
            if rc < 0 {
                return Err(Error::in_context(
                    rc,
                    &format!("{}: recording", self.port()),
                ));
            }
        }
    }

    /// The stream as an iterator of samples (read from the session in
    /// batches). Starts the stream when it is not running and stops it when
    /// the iterator is dropped. Ends with an `Err` item when the stream is
    /// lost; gaps, tare changes and reconnects are in [`Stream::events`].
    ///
    /// ```
    /// let mut s = leptrino::Sensor::open_sim(&leptrino::SimOptions::new(), &Default::default())?;
    /// let samples: Vec<_> = s.stream()?.take(50).collect::<Result<_, _>>()?;
    /// assert!(samples.windows(2).all(|w| w[1].seq == w[0].seq.wrapping_add(1)));
    /// assert!(!s.streaming());
    /// # Ok::<(), leptrino::Error>(())
    /// ```
    pub fn stream(&mut self) -> Result<Stream<'_>> {
        let started = !self.streaming();
        if started {
            self.start()?;
        }
        Ok(Stream {
            sensor: self,
            started,
            buf: Recording::with_capacity(ITER_BATCH),
            pos: 0,
            rows: 0,
            events: Vec::new(),
            done: false,
        })
    }
}

/// Append up to `room` samples to rec from the session; (status, samples added).
fn read_into(
    s: *mut sys::lep_session,
    rec: &mut Recording,
    room: usize,
    timeout_ms: i32,
) -> (i32, usize) {
    append(rec, room, |c, n| {
        // SAFETY: a driving-thread call on an open session; every column
        // has room for `room` rows from c on, n a valid out pointer.
        unsafe {
            sys::lep_session_read(
                s, timeout_ms, room, n, c.t_mono, c.t_utc, c.si, c.raw, c.zeroed, c.status,
                c.flags, c.seq,
            )
        }
    })
}

/// Where the next row of each column of a Recording goes.
struct Columns {
    t_mono: *mut f64,
    t_utc: *mut f64,
    si: *mut f64,
    raw: *mut i16,
    zeroed: *mut f64,
    status: *mut u8,
    flags: *mut u8,
    seq: *mut u16,
}

/// Let `fill` write up to `room` rows into the columns' spare capacity
/// (lep_session_read and lep_session_read_one write rows from the pointers
/// they are given and say how many: `fill`'s second argument); append them.
/// (its status, rows added).
fn append(
    rec: &mut Recording,
    room: usize,
    fill: impl FnOnce(&Columns, &mut usize) -> i32,
) -> (i32, usize) {
    let n = rec.len();
    rec.t.reserve(room);
    rec.t_utc.reserve(room);
    rec.raw.reserve(room);
    rec.zeroed.reserve(room);
    rec.si.reserve(room);
    rec.status.reserve(room);
    rec.flags.reserve(room);
    rec.seq.reserve(room);
    // Every column has room for n + room rows ([f64; 6] and [i16; 6] rows
    // are 6 contiguous values, as the library's [cap*6] arrays); the
    // pointers are to row n, within each allocation.
    let c = Columns {
        t_mono: rec.t.spare_capacity_mut().as_mut_ptr().cast(),
        t_utc: rec.t_utc.spare_capacity_mut().as_mut_ptr().cast(),
        si: rec.si.spare_capacity_mut().as_mut_ptr().cast(),
        raw: rec.raw.spare_capacity_mut().as_mut_ptr().cast(),
        zeroed: rec.zeroed.spare_capacity_mut().as_mut_ptr().cast(),
        status: rec.status.spare_capacity_mut().as_mut_ptr().cast(),
        flags: rec.flags.spare_capacity_mut().as_mut_ptr().cast(),
        seq: rec.seq.spare_capacity_mut().as_mut_ptr().cast(),
    };
    let mut added = 0usize;
    let rc = fill(&c, &mut added);
    let m = n + added.min(room);
    // SAFETY: rows n..m of every column were written by the library.
    unsafe {
        rec.t.set_len(m);
        rec.t_utc.set_len(m);
        rec.raw.set_len(m);
        rec.zeroed.set_len(m);
        rec.si.set_len(m);
        rec.status.set_len(m);
        rec.flags.set_len(m);
        rec.seq.set_len(m);
    }
    (rc, m - n)
}

impl Recording {
    fn clear_rows(&mut self) {
        self.t.clear();
        self.t_utc.clear();
        self.raw.clear();
        self.zeroed.clear();
        self.si.clear();
        self.status.clear();
        self.flags.clear();
        self.seq.clear();
    }
}

/// Iterator of stream samples from [`Sensor::stream`]; stops the stream when
/// dropped if it started it.
pub struct Stream<'a> {
    sensor: &'a mut Sensor,
    started: bool,
    buf: Recording,
    pos: usize,
    /// rows read by this iterator: its events' `sample` count from its start
    rows: u64,
    events: Vec<Event>,
    done: bool,
}

impl fmt::Debug for Stream<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Stream")
            .field("port", &self.sensor.port())
            .field("events", &self.events.len())
            .finish()
    }
}

impl Stream<'_> {
    /// Events read so far (gaps, tare, reconnects, overloads), their
    /// `sample` counted from this iterator's first sample.
    pub fn events(&self) -> &[Event] {
        &self.events
    }

    /// Take the events read so far.
    pub fn take_events(&mut self) -> Vec<Event> {
        std::mem::take(&mut self.events)
    }

    /// Begin a tare over the next n samples while the stream goes on.
    pub fn begin_tare(&self, n: u32) -> Result<()> {
        self.sensor.control.begin_tare(n)
    }

    /// The sensor's any-thread calls (untare, health, ...).
    pub fn control(&self) -> &Control {
        &self.sensor.control
    }

    fn fill(&mut self) -> Option<Result<()>> {
        loop {
            self.buf.clear_rows();
            self.pos = 0;
            let s = &mut *self.sensor;
            let (rc, n) = read_into(s.ptr(), &mut self.buf, ITER_BATCH, s.timeout_ms);
            let mut new = s.drain_events(Some(self.rows));
            self.rows += n as u64;
            self.events.append(&mut new);
            if n > 0 {
                return Some(Ok(()));
            }
            if rc == sys::LEP_E_END {
                return None;
            }
            if rc == sys::LEP_E_TIMEOUT {
                continue; // nothing in this wait (a lost stream is LEP_E_LOST)
            }
            if rc < 0 {
                return Some(Err(Error::in_context(
                    rc,
                    &format!("{}: waiting for stream data", s.port()),
                )));
            }
        }
    }

    fn finish(&mut self) {
        self.done = true;
        if self.started {
            self.started = false;
            if self.sensor.streaming() {
                let _ = self.sensor.stop();
            }
        }
    }
}

impl Iterator for Stream<'_> {
    type Item = Result<Sample>;

    fn next(&mut self) -> Option<Result<Sample>> {
        if self.done {
            return None;
        }
        if self.pos >= self.buf.len() {
            match self.fill() {
                Some(Ok(())) => {}
                Some(Err(e)) => {
                    self.finish();
                    return Some(Err(e));
                }
                None => {
                    self.finish();
                    return None;
                }
            }
        }
        let x = self.buf.sample(self.pos);
        self.pos += 1;
        Some(Ok(x))
    }
}

impl Drop for Stream<'_> {
    fn drop(&mut self) {
        self.finish();
    }
}
