//! A sensor through the library's host session (leptrino/session.h).
//!
//! Everything the session does (start-up recovery, tare, host low-pass,
//! decimation, rotation, gap detection, reconnect, health, metadata) runs in
//! C; this module moves its batches into plain vectors and turns its structs
//! into Rust values.

use std::cell::Cell;
use std::ffi::{c_char, CStr, CString};
use std::fmt;
use std::marker::PhantomData;
use std::ptr::NonNull;
use std::sync::Arc;
use std::time::Duration;

use leptrino_sys as sys;

use crate::error::{check, Error, Result};
use crate::sim::{SimOptions, VirtualSensor};
use crate::values::{Event, ProductInfo, Rated, Recording, Sample};

/// Samples per `lep_session_read` of the sample iterator.
const ITER_BATCH: usize = 256;
/// Longest wait of one `lep_session_read` in record().
const RECORD_SLICE_S: f64 = 0.25;
/// record() returns only at its end, so it lets the library hold samples back
/// this long (ms) to save wake-ups; the sensor's own budget comes back after.
const RECORD_LATENCY_MS: i32 = 100;
/// Reads after the end of record(duration) that collect what the budget held back.
const RECORD_FINAL_READS: u32 = 64;

/// Health since the stream started (`lep_session_health`): measured against
/// nominal rate, samples lost, gaps, errors, overloads, reconnects.
pub type Health = sys::lep_session_health;

fn ms(d: Duration) -> i32 {
    i32::try_from(d.as_nanos().div_ceil(1_000_000)).unwrap_or(i32::MAX)
}

fn monotonic() -> f64 {
    // SAFETY: no arguments, no state.
    unsafe { sys::lep_monotonic_seconds() }
}

/// Options of a session; start from [`Options::new`] (the library's defaults,
/// `lep_session_options_init`) and change what you need. The library checks
/// them when the sensor is opened (`ErrorKind::Arg` with a message).
///
/// ```
/// use std::time::Duration;
/// let o = leptrino::Options::new()
///     .tare(100)
///     .lowpass(50.0)
///     .reconnect(true)
///     .data_timeout(Duration::from_secs(1));
/// # let _ = o;
/// ```
#[derive(Clone)]
pub struct Options {
    raw: sys::lep_session_options,
}

// SAFETY: the one pointer of lep_session_options, port, is always NULL in an
// Options (open sets it in a copy of its own, for the call only).
unsafe impl Send for Options {}
// SAFETY: as above; nothing is shared through &Options.
unsafe impl Sync for Options {}

impl Default for Options {
    fn default() -> Self {
        Options::new()
    }
}

impl fmt::Debug for Options {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let o = &self.raw;
        f.debug_struct("Options")
            .field("timeout_ms", &o.timeout_ms)
            .field("data_timeout_ms", &o.data_timeout_ms)
            .field("latency_ms", &o.latency_ms)
            .field("reconnect", &o.reconnect)
            .field("tare_samples", &o.tare_samples)
            .field("lowpass_hz", &o.lowpass_hz)
            .field("decimate", &o.decimate)
            .finish_non_exhaustive()
    }
}

impl Options {
    /// The library's defaults.
    pub fn new() -> Options {
        let mut raw = sys::lep_session_options::default();
        // SAFETY: valid, writable options.
        unsafe { sys::lep_session_options_init(&mut raw) };
        Options { raw }
    }
    /// Answer timeout per attempt of a command (default 500 ms); also how
    /// long one read waits for stream data.
    pub fn timeout(mut self, d: Duration) -> Options {
        self.raw.timeout_ms = ms(d);
        self
    }
    /// No sample for this long while streaming is a disconnect (default 2 s).
    pub fn data_timeout(mut self, d: Duration) -> Options {
        self.raw.data_timeout_ms = ms(d);
        self
    }
    /// How long delivery may hold samples back to save wake-ups (default 0:
    /// each sample as soon as it is read, for a control loop).
    pub fn latency(mut self, d: Duration) -> Options {
        self.raw.latency_ms = ms(d);
        self
    }
    /// After a disconnect or data timeout, reopen with backoff and go on
    /// (reported as events).
    pub fn reconnect(mut self, on: bool) -> Options {
        self.raw.reconnect = on;
        self
    }
    /// Tare over the first n samples after the stream starts (not delivered).
    pub fn tare(mut self, n: u32) -> Options {
        self.raw.tare_samples = n;
        self
    }
    /// Host low-pass cut-off on SI values, Hz (0 off).
    pub fn lowpass(mut self, hz: f64) -> Options {
        self.raw.lowpass_hz = hz;
        self
    }
    /// Deliver every nth sample (after the low-pass).
    pub fn decimate(mut self, n: u32) -> Options {
        self.raw.decimate = n;
        self
    }
    /// A hole longer than this many nominal periods is a gap (default 3).
    pub fn gap_periods(mut self, periods: f64) -> Options {
        self.raw.gap_periods = periods;
        self
    }
    /// Output frame: row-major rotation matrix R (force = R f, moment = R m).
    pub fn rotation(mut self, r: [f64; 9]) -> Options {
        self.raw.rotation = r;
        self
    }
    /// Moment reference point in the output frame, metres.
    pub fn shift(mut self, m: [f64; 3]) -> Options {
        self.raw.shift_m = m;
        self
    }
}

/// The session pointer, shared by a [`Sensor`] and its [`Control`]s; closed
/// when the last of them goes.
struct Session(NonNull<sys::lep_session>);

// SAFETY: session.h: "one thread drives a session" (any one, one at a time:
// only Sensor makes those calls, and Sensor is not Sync); the calls Control
// makes (tare, untare, set/get tare, low-pass, rotation, health, metadata)
// "may also be called from other threads at any time".
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
        // SAFETY: any-thread call; off holds LEP_AXES doubles.
        unsafe { sys::lep_session_get_tare(self.ptr(), off.as_mut_ptr()) };
        off
    }

    /// Set the tare offsets, counts.
    pub fn set_tare_offsets(&self, counts: [f64; 6]) -> Result<()> {
        // SAFETY: any-thread call; counts holds LEP_AXES doubles.
        let rc = unsafe { sys::lep_session_set_tare(self.ptr(), counts.as_ptr()) };
        check(rc, &format!("{}: tare offsets", self.port))
    }

    /// True while a tare is in force.
    pub fn tared(&self) -> bool {
        let mut off = [0.0; 6];
        // SAFETY: as tare_offsets.
        unsafe { sys::lep_session_get_tare(self.ptr(), off.as_mut_ptr()) }
    }

    /// Change the host low-pass cut-off, Hz (0 off; `ErrorKind::Value` above
    /// 0.45 x the rate).
    pub fn set_lowpass(&self, hz: f64) -> Result<()> {
        // SAFETY: any-thread call.
        check(
            unsafe { sys::lep_session_set_lowpass(self.ptr(), hz) },
            &format!("{}: low-pass {hz} Hz", self.port),
        )
    }

    /// Change the output frame (rotation row-major, moment point in metres);
    /// `ErrorKind::Value` for a matrix that is not orthonormal.
    pub fn set_frame(&self, rotation: [f64; 9], shift_m: [f64; 3]) -> Result<()> {
        // SAFETY: any-thread call; 9 and 3 doubles.
        let rc = unsafe {
            sys::lep_session_set_rotation(self.ptr(), rotation.as_ptr(), shift_m.as_ptr())
        };
        check(rc, &format!("{}: output frame", self.port))
    }

    /// Limits on the SI values, per axis (N, N·m; 0: none): a sample beyond
    /// one is flagged and `LimitExceeded` / `LimitCleared` events mark the
    /// episodes. `ErrorKind::Arg` for negative or non-finite limits.
    pub fn set_limits(&self, limits: [f64; 6]) -> Result<()> {
        // SAFETY: any-thread call; 6 doubles.
        let rc = unsafe { sys::lep_session_set_limits(self.ptr(), limits.as_ptr()) };
        check(rc, &format!("{}: limits", self.port))
    }

    /// Health since the stream started.
    pub fn health(&self) -> Health {
        let mut h = Health::default();
        // SAFETY: any-thread call, valid out pointer.
        unsafe { sys::lep_session_get_health(self.ptr(), &mut h) };
        h
    }

    fn metadata_struct(&self) -> sys::lep_session_metadata {
        let mut m = sys::lep_session_metadata::default();
        // SAFETY: any-thread call, valid out pointer.
        unsafe { sys::lep_session_get_metadata(self.ptr(), &mut m) };
        m
    }

    /// The metadata as the library writes it in every recording: one JSON
    /// object (model, serial, firmware, rated values, filters, tare, frame,
    /// start time, library version).
    pub fn metadata_json(&self) -> Result<String> {
        let mut cap = 4096;
        loop {
            let mut buf = vec![0u8; cap];
            let mut len = 0usize;
            // SAFETY: any-thread call; buf of cap bytes, len out pointer.
            let rc = unsafe {
                sys::lep_session_metadata_json(
                    self.ptr(),
                    buf.as_mut_ptr().cast::<c_char>(),
                    cap,
                    &mut len,
                )
            };
            if rc == sys::LEP_E_BUFFER && cap < 1 << 20 {
                cap *= 4;
                continue;
            }
            check(rc, &format!("{}: metadata", self.port))?;
            buf.truncate(len);
            return Ok(String::from_utf8_lossy(&buf).into_owned());
        }
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
    /// samples delivered since the stream started: the events' sample base
    delivered: u64,
    start_mono: f64,
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
        let cport = CString::new(port)
            .map_err(|_| Error::arg(format!("port {port:?}: contains a NUL byte")))?;
        let mut raw = options.raw;
        raw.use_sim = false;
        raw.port = cport.as_ptr();
        Sensor::open_raw(&raw, port)
    }

    /// Open a virtual sensor that the session starts itself (and stops when
    /// closed); [`simulator`](Self::simulator) reaches it for fault injection.
    pub fn open_sim(sim: &SimOptions, options: &Options) -> Result<Sensor> {
        let mut raw = options.raw;
        raw.use_sim = true;
        raw.sim = sim.raw;
        raw.port = std::ptr::null();
        Sensor::open_raw(&raw, "virtual sensor")
    }

    fn open_raw(raw: &sys::lep_session_options, what: &str) -> Result<Sensor> {
        let mut out: *mut sys::lep_session = std::ptr::null_mut();
        let mut err = [0u8; 512];
        // SAFETY: valid options (copied at open; the port string outlives the
        // call), out pointer, err buffer of its size.
        let rc =
            unsafe { sys::lep_session_open(raw, &mut out, err.as_mut_ptr().cast(), err.len()) };
        crate::error::check_msg(rc, &err, what)?;
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
        let meta = control.metadata_struct();
        Ok(Sensor {
            info: ProductInfo::from_c(&meta.info),
            rated: Rated::from_c(&meta.rated),
            nominal_hz: if meta.nominal_hz > 0.0 {
                meta.nominal_hz
            } else {
                sys::LEP_SESSION_NOMINAL_HZ
            },
            decimate: raw.decimate.max(1),
            timeout_ms: raw.timeout_ms.max(1),
            control,
            delivered: 0,
            start_mono: 0.0,
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
        unsafe { sys::lep_session_streaming(self.ptr()) }
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
        self.check_cmd(rc, "starting the stream")?;
        self.delivered = 0;
        self.start_mono = self.control.metadata_struct().start_mono;
        Ok(())
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
        let (rc, _) = append(&mut one, 1, |b| {
            // SAFETY: driving-thread call; b has room for one row.
            unsafe { sys::lep_session_read_one(self.ptr(), b) }
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
        while unsafe { sys::lep_session_taring(self.ptr()) } {
            scratch.clear_rows();
            let (rc, n) = read_into(self.ptr(), &mut scratch, ITER_BATCH, self.timeout_ms);
            self.delivered += n as u64;
            let mut new = self.drain_events(0);
            self.events.append(&mut new);
            if rc < 0 && rc != sys::LEP_E_END {
                return Err(self.cmd_error(rc, "tare"));
            }
        }
        Ok(())
    }

    fn drain_events(&mut self, base: u64) -> Vec<Event> {
        let mut out = Vec::new();
        let mut ev = sys::lep_session_event::default();
        // SAFETY: driving-thread call, valid out pointer.
        while unsafe { sys::lep_session_next_event(self.ptr(), &mut ev) } {
            out.push(Event::from_c(&ev, base, self.start_mono));
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
        let base = self.delivered;
        // SAFETY: driving-thread calls.
        let latency_before = unsafe { sys::lep_session_latency(self.ptr()) };
        if latency_before < RECORD_LATENCY_MS {
            unsafe { sys::lep_session_set_latency(self.ptr(), RECORD_LATENCY_MS) };
        }
        let result = self.record_loop(&mut rec, seconds, count, rate, base);
        unsafe { sys::lep_session_set_latency(self.ptr(), latency_before) };
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
        base: u64,
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
                        // SAFETY: driving-thread call.
                        unsafe { sys::lep_session_set_latency(self.ptr(), 0) };
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
            self.delivered += added as u64;
            let mut new = self.drain_events(base);
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
        let base = self.delivered;
        Ok(Stream {
            sensor: self,
            started,
            buf: Recording::with_capacity(ITER_BATCH),
            pos: 0,
            base,
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
    append(rec, room, |b| {
        // SAFETY: a driving-thread call on an open session; b as append says.
        unsafe { sys::lep_session_read(s, b, timeout_ms) }
    })
}

/// Let `fill` append up to `room` rows to rec through a `lep_session_batch`
/// pointing into the columns' spare capacity (lep_session_read and
/// lep_session_read_one append rows n..b.n to every column, nothing else);
/// (its status, rows added).
fn append(
    rec: &mut Recording,
    room: usize,
    fill: impl FnOnce(&mut sys::lep_session_batch) -> i32,
) -> (i32, usize) {
    let n = rec.len();
    let cap = n + room;
    rec.t.reserve(room);
    rec.t_utc.reserve(room);
    rec.raw.reserve(room);
    rec.zeroed.reserve(room);
    rec.si.reserve(room);
    rec.status.reserve(room);
    rec.flags.reserve(room);
    rec.seq.reserve(room);
    // Every column has room for cap rows ([f64; 6] and [i16; 6] rows are 6
    // contiguous values, as the batch's [cap*6] arrays).
    let mut b = sys::lep_session_batch {
        cap,
        n,
        t_mono: rec.t.as_mut_ptr(),
        t_utc: rec.t_utc.as_mut_ptr(),
        raw: rec.raw.as_mut_ptr().cast::<i16>(),
        zeroed: rec.zeroed.as_mut_ptr().cast::<f64>(),
        si: rec.si.as_mut_ptr().cast::<f64>(),
        status: rec.status.as_mut_ptr(),
        flags: rec.flags.as_mut_ptr(),
        seq: rec.seq.as_mut_ptr(),
    };
    let rc = fill(&mut b);
    let m = b.n.clamp(n, cap);
    // SAFETY: rows n..m of every column were written by the session.
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
    base: u64,
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
            s.delivered += n as u64;
            let mut new = s.drain_events(self.base);
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
