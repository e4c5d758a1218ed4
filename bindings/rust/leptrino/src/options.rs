//! Options by name (leptrino/options.h): one options handle of the library
//! behind [`Options`] (the session's) and [`SimOptions`](crate::SimOptions)
//! (the virtual sensor's "sim-*"). Names, types, ranges, defaults and the
//! messages of a refusal all come from the library's one table: nothing here
//! knows a layout.

use std::ffi::{c_char, CStr, CString};
use std::fmt;
use std::ptr::NonNull;
use std::sync::Mutex;
use std::time::Duration;

use leptrino_sys as sys;

use crate::error::{check_msg, text_result, Error, Result};
use crate::values::Payload;

/// Room for the one-line messages of the option setters.
const ERR_LEN: usize = 256;

pub(crate) fn cstring(what: &str, s: &str) -> Result<CString> {
    CString::new(s).map_err(|_| Error::arg(format!("{what} {s:?}: contains a NUL byte")))
}

/// A static string of the library (the option table's), "" for NULL.
pub(crate) fn static_str(p: *const c_char) -> &'static str {
    if p.is_null() {
        return "";
    }
    // SAFETY: the table's strings are static, NUL-terminated (options.h).
    unsafe { CStr::from_ptr(p) }.to_str().unwrap_or("")
}

/// The rows of the option table, as (index, name, scope).
pub(crate) fn table() -> impl Iterator<Item = (usize, &'static str, i32)> {
    // SAFETY: the table functions are re-entrant and take any index.
    let n = unsafe { sys::lep_option_count() };
    (0..n).map(|i| {
        let name = static_str(unsafe { sys::lep_option_name(i) });
        (i, name, unsafe { sys::lep_option_scope(i) })
    })
}

pub(crate) fn ms(d: Duration) -> i64 {
    i64::try_from(d.as_nanos().div_ceil(1_000_000)).unwrap_or(i64::MAX)
}

struct Ptr(NonNull<sys::lep_options>);

// SAFETY: a handle belongs to its caller and has no thread affinity
// (options.h: "one thread at a time"); Handle keeps it behind a Mutex.
unsafe impl Send for Ptr {}

/// An owned `lep_options` handle. `&mut` calls reach it directly; `&` calls
/// (the getters, a copy) lock, so the handle is used by one thread at a time
/// as options.h asks, and `Handle` is `Send + Sync`.
pub(crate) struct Handle(Mutex<Ptr>);

impl Handle {
    pub(crate) fn new() -> Handle {
        // SAFETY: no arguments; NULL only when out of memory.
        let p = unsafe { sys::lep_options_new() };
        Handle(Mutex::new(Ptr(
            NonNull::new(p).expect("lep_options_new: out of memory")
        )))
    }

    fn ptr_mut(&mut self) -> *mut sys::lep_options {
        self.0
            .get_mut()
            .unwrap_or_else(|e| e.into_inner())
            .0
            .as_ptr()
    }

    /// Run f on the handle, locked.
    pub(crate) fn with<R>(&self, f: impl FnOnce(*const sys::lep_options) -> R) -> R {
        let g = self.0.lock().unwrap_or_else(|e| e.into_inner());
        f(g.0.as_ptr())
    }

    fn set_with(
        &mut self,
        name: &str,
        what: &str,
        f: impl FnOnce(*mut sys::lep_options, *const c_char, *mut c_char, usize) -> i32,
    ) -> Result<()> {
        let cname = cstring("option", name)?;
        let mut err = [0u8; ERR_LEN];
        let rc = f(
            self.ptr_mut(),
            cname.as_ptr(),
            err.as_mut_ptr().cast(),
            err.len(),
        );
        check_msg(rc, &err, &format!("{what} {name}"))
    }

    pub(crate) fn set_text(&mut self, name: &str, value: &str) -> Result<()> {
        let v = cstring(name, value)?;
        // SAFETY: an owned handle, NUL-terminated strings, err of its size.
        self.set_with(name, "option", |o, n, e, l| unsafe {
            sys::lep_options_set(o, n, v.as_ptr(), e, l)
        })
    }

    pub(crate) fn set_int(&mut self, name: &str, value: i64) -> Result<()> {
        // SAFETY: as set_text.
        self.set_with(name, "option", |o, n, e, l| unsafe {
            sys::lep_options_set_int(o, n, value, e, l)
        })
    }

    pub(crate) fn set_double(&mut self, name: &str, value: f64) -> Result<()> {
        // SAFETY: as set_text.
        self.set_with(name, "option", |o, n, e, l| unsafe {
            sys::lep_options_set_double(o, n, value, e, l)
        })
    }

    pub(crate) fn set_doubles(&mut self, name: &str, values: &[f64]) -> Result<()> {
        // SAFETY: as set_text; values holds values.len() doubles.
        self.set_with(name, "option", |o, n, e, l| unsafe {
            sys::lep_options_set_doubles(o, n, values.as_ptr(), values.len(), e, l)
        })
    }

    pub(crate) fn get_text(&self, name: &str) -> Result<String> {
        let cname = cstring("option", name)?;
        let context = format!("option {name:?}: unknown");
        self.with(|o| {
            // SAFETY: a live handle; buf holds cap bytes (or is NULL with cap 0).
            text_result(
                |buf, cap, len| unsafe { sys::lep_options_get(o, cname.as_ptr(), buf, cap, len) },
                &context,
            )
        })
    }
}

impl Clone for Handle {
    fn clone(&self) -> Handle {
        // SAFETY: a live handle; the copy is a new one we own.
        let p = self.with(|o| unsafe { sys::lep_options_copy(o) });
        Handle(Mutex::new(Ptr(
            NonNull::new(p).expect("lep_options_copy: out of memory")
        )))
    }
}

impl Drop for Handle {
    fn drop(&mut self) {
        // SAFETY: made by lep_options_new or _copy, freed once.
        unsafe { sys::lep_options_free(self.ptr_mut()) }
    }
}

/// Options of a session; start from [`Options::new`] (the library's
/// defaults) and change what you need, with the builder methods or by name
/// ([`set`](Options::set): any option of the library's table, as the
/// `leptrino` tool's `--NAME VALUE`). The library checks each value when it
/// is set; a builder method keeps the first refusal and
/// [`Sensor::open_with`](crate::Sensor::open_with) returns it
/// (`ErrorKind::Arg` with the library's message).
///
/// ```
/// use std::time::Duration;
/// let mut o = leptrino::Options::new()
///     .tare(100)
///     .lowpass(50.0)
///     .reconnect(true)
///     .data_timeout(Duration::from_secs(1));
/// o.set("gap-periods", 5)?.set("limit", "fz=50,mz=2")?;
/// assert_eq!(o.get("lowpass")?, "50");
/// assert_eq!(o.set("lowpas", 1).unwrap_err().message(), "unknown option 'lowpas'");
/// # Ok::<(), leptrino::Error>(())
/// ```
#[derive(Clone)]
pub struct Options {
    pub(crate) h: Handle,
    /// The first refusal of a builder method: (code, message).
    deferred: Option<(i32, String)>,
}

impl Default for Options {
    fn default() -> Self {
        Options::new()
    }
}

impl fmt::Debug for Options {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut d = f.debug_struct("Options");
        for name in Options::names() {
            if let Ok(v) = self.h.get_text(name) {
                d.field(name, &v);
            }
        }
        if let Some((_, msg)) = &self.deferred {
            d.field("error", msg);
        }
        d.finish()
    }
}

impl Options {
    /// The library's defaults (`lep_options_new`).
    pub fn new() -> Options {
        Options {
            h: Handle::new(),
            deferred: None,
        }
    }

    fn apply(mut self, f: impl FnOnce(&mut Handle) -> Result<()>) -> Options {
        if self.deferred.is_none() {
            if let Err(e) = f(&mut self.h) {
                self.deferred = Some((e.code(), e.message().to_owned()));
            }
        }
        self
    }

    /// The first refusal of a builder method, if any.
    pub(crate) fn deferred_error(&self) -> Option<Error> {
        self.deferred
            .as_ref()
            .map(|(code, msg)| Error::with_message(*code, msg.clone()))
    }

    /// Set an option by name from text (`lep_options_set`): "data-timeout"
    /// or "data_timeout", the value as the `leptrino` tool takes it (flags
    /// `true`/`false`/`1`/`0`, lists "a,b,c"). An unknown name or a bad value
    /// is `ErrorKind::Arg` with the library's message naming it, and changes
    /// nothing. The virtual sensor's "sim-*" options are
    /// [`SimOptions`](crate::SimOptions)'.
    pub fn set(&mut self, name: &str, value: impl fmt::Display) -> Result<&mut Options> {
        self.h.set_text(name, &value.to_string())?;
        Ok(self)
    }

    /// The value of an option, as text [`set`](Self::set) accepts.
    pub fn get(&self, name: &str) -> Result<String> {
        self.h.get_text(name)
    }

    /// The session's option names, from the library's table (without the
    /// virtual sensor's "sim-*").
    pub fn names() -> Vec<&'static str> {
        table()
            .filter(|&(_, _, scope)| scope != sys::LEP_SCOPE_SIM as i32)
            .map(|(_, name, _)| name)
            .collect()
    }

    /// Answer timeout per attempt of a command (default 500 ms); also how
    /// long one read waits for stream data.
    pub fn timeout(self, d: Duration) -> Options {
        self.apply(|h| h.set_int("timeout", ms(d)))
    }
    /// No sample for this long while streaming is a disconnect (default 2 s).
    pub fn data_timeout(self, d: Duration) -> Options {
        self.apply(|h| h.set_int("data-timeout", ms(d)))
    }
    /// How long delivery may hold samples back to save wake-ups (default 0:
    /// each sample as soon as it is read, for a control loop).
    pub fn latency(self, d: Duration) -> Options {
        self.apply(|h| h.set_int("latency", ms(d)))
    }
    /// After a disconnect or data timeout, reopen with backoff and go on
    /// (reported as events).
    pub fn reconnect(self, on: bool) -> Options {
        self.apply(|h| h.set_int("reconnect", i64::from(on)))
    }
    /// Tare over the first n samples after the stream starts (not delivered).
    pub fn tare(self, n: u32) -> Options {
        self.apply(|h| h.set_int("tare-samples", i64::from(n)))
    }
    /// Host low-pass cut-off on SI values, Hz (0 off).
    pub fn lowpass(self, hz: f64) -> Options {
        self.apply(|h| h.set_double("lowpass", hz))
    }
    /// Deliver every nth sample (after the low-pass).
    pub fn decimate(self, n: u32) -> Options {
        self.apply(|h| h.set_int("decimate", i64::from(n)))
    }
    /// A hole longer than this many nominal periods is a gap (default 3).
    pub fn gap_periods(self, periods: f64) -> Options {
        self.apply(|h| h.set_double("gap-periods", periods))
    }
    /// Output frame: row-major rotation matrix R (force = R f, moment = R m).
    pub fn rotation(self, r: [f64; 9]) -> Options {
        self.apply(|h| h.set_doubles("rotation", &r))
    }
    /// Moment reference point in the output frame, metres.
    pub fn shift(self, m: [f64; 3]) -> Options {
        self.apply(|h| h.set_doubles("shift", &m))
    }
    /// A tool on the sensor whose gravity wrench is removed from the SI
    /// values (`None`: none); see [`Control::set_payload`](crate::Control::set_payload).
    pub fn payload(self, payload: Option<Payload>) -> Options {
        let v = payload.unwrap_or_default().to_array();
        self.apply(|h| h.set_doubles("payload", &v))
    }
    /// Gravity in the sensor frame, m/s² (default (0, 0, -9.80665): the z
    /// axis up).
    pub fn gravity(self, g: [f64; 3]) -> Options {
        self.apply(|h| h.set_doubles("gravity", &g))
    }
    /// Limits on the SI values per axis, N and N·m (0: none); see
    /// [`Control::set_limits`](crate::Control::set_limits).
    pub fn limits(self, limits: [f64; 6]) -> Options {
        self.apply(|h| h.set_doubles("limit", &limits))
    }
}
