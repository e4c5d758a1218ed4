//! Errors: every `LEP_E_*` code of the library, with the library's message.

use std::ffi::{c_char, CStr};
use std::fmt;

use leptrino_sys as sys;

pub use sys::ErrorKind;

use crate::Recording;

/// A failure reported by libleptrino (a `LEP_E_*` code), or a bad argument
/// refused before the call (`ErrorKind::Arg`).
///
/// [`code`](Error::code) is the C code; [`kind`](Error::kind) the same as an
/// enum generated from `leptrino/error.h`. The message names the port or the
/// option, as the library wrote it. An error that ends a recording carries
/// what was recorded until then ([`recording`](Error::recording)): nothing is
/// lost.
///
/// ```
/// let err = leptrino::Sensor::open("/dev/leptrino-no-such-port").unwrap_err();
/// assert_eq!(err.kind(), leptrino::ErrorKind::NotFound);
/// assert_eq!(err.code(), leptrino::sys::LEP_E_NOT_FOUND);
/// assert!(err.to_string().contains("/dev/leptrino-no-such-port"));
/// ```
pub struct Error {
    code: i32,
    message: String,
    sensor_result: Option<u8>,
    recording: Option<Box<Recording>>,
}

/// `Result` with [`Error`].
pub type Result<T> = std::result::Result<T, Error>;

/// The library's description of a code (`lep_strerror`).
pub(crate) fn strerror(code: i32) -> String {
    // SAFETY: lep_strerror returns a static, never-NULL, NUL-terminated string.
    unsafe { CStr::from_ptr(sys::lep_strerror(code)) }
        .to_string_lossy()
        .into_owned()
}

impl Error {
    /// An error with the library's complete message (what it wrote into err).
    pub(crate) fn with_message(code: i32, message: impl Into<String>) -> Error {
        Error {
            code,
            message: message.into(),
            sensor_result: None,
            recording: None,
        }
    }

    /// An error in a context ("/dev/ttyACM0: recording"): the message is the
    /// context and the code's description.
    pub(crate) fn in_context(code: i32, context: &str) -> Error {
        Error::with_message(code, format!("{context}: {}", strerror(code)))
    }

    /// A bad argument caught on the Rust side.
    pub(crate) fn arg(message: impl Into<String>) -> Error {
        Error::with_message(sys::LEP_E_ARG, message)
    }

    pub(crate) fn set_sensor_result(mut self, result: u8) -> Error {
        self.sensor_result = Some(result);
        self
    }

    pub(crate) fn set_recording(mut self, rec: Recording) -> Error {
        self.recording = Some(Box::new(rec));
        self
    }

    /// The C code, a negative `LEP_E_*` value.
    pub fn code(&self) -> i32 {
        self.code
    }

    /// The code as an enum. The enum is generated from the header of the
    /// library this crate links, so it knows every code that library returns.
    pub fn kind(&self) -> ErrorKind {
        ErrorKind::from_code(self.code).unwrap_or(ErrorKind::Unexpected)
    }

    /// The message: what failed, where, and why.
    pub fn message(&self) -> &str {
        &self.message
    }

    /// With `ErrorKind::Sensor`: the sensor's result code (`LEP_RESULT_*`).
    pub fn sensor_result(&self) -> Option<u8> {
        self.sensor_result
    }

    /// The samples and events recorded before the error (record() only).
    pub fn recording(&self) -> Option<&Recording> {
        self.recording.as_deref()
    }

    /// Take the partial recording out of the error.
    pub fn into_recording(self) -> Option<Recording> {
        self.recording.map(|r| *r)
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)?;
        if let Some(r) = self.sensor_result {
            // SAFETY: static, never-NULL string.
            let text = unsafe { CStr::from_ptr(sys::lep_result_str(r)) };
            write!(f, " (sensor result 0x{r:02x}: {})", text.to_string_lossy())?;
        }
        Ok(())
    }
}

impl fmt::Debug for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Error")
            .field("kind", &self.kind())
            .field("code", &self.code)
            .field("message", &self.message)
            .field("sensor_result", &self.sensor_result)
            .field("recording", &self.recording.as_ref().map(|r| r.len()))
            .finish()
    }
}

impl std::error::Error for Error {}

/// A C status (LEP_OK or a LEP_E_* code) as a Result, with a context.
pub(crate) fn check(rc: i32, context: &str) -> Result<()> {
    if rc < 0 {
        Err(Error::in_context(rc, context))
    } else {
        Ok(())
    }
}

/// The text the library wrote into an err buffer.
pub(crate) fn buf_text(buf: &[u8]) -> String {
    let end = buf.iter().position(|&b| b == 0).unwrap_or(buf.len());
    String::from_utf8_lossy(&buf[..end]).into_owned()
}

/// A C status and the library's message buffer as a Result.
pub(crate) fn check_msg(rc: i32, buf: &[u8], fallback: &str) -> Result<()> {
    if rc >= 0 {
        return Ok(());
    }
    let msg = buf_text(buf);
    Err(if msg.is_empty() {
        Error::in_context(rc, fallback)
    } else {
        Error::with_message(rc, msg)
    })
}

/// A text result under the library's text rule (leptrino/options.h): `f(buf,
/// cap, len)` writes the text and a NUL when they fit and always sets *len to
/// the text's length; LEP_E_BUFFER when not. Asks for the size first.
pub(crate) fn text_result(
    mut f: impl FnMut(*mut c_char, usize, *mut usize) -> i32,
    context: &str,
) -> Result<String> {
    let mut len = 0usize;
    let rc = f(std::ptr::null_mut(), 0, &mut len);
    if rc < 0 && rc != sys::LEP_E_BUFFER {
        return Err(Error::in_context(rc, context));
    }
    // The text may grow between the two calls (a session's metadata): ask again.
    for _ in 0..8 {
        let mut buf = vec![0u8; len + 1];
        let rc = f(buf.as_mut_ptr().cast(), buf.len(), &mut len);
        if rc == sys::LEP_E_BUFFER {
            continue;
        }
        check(rc, context)?;
        buf.truncate(len.min(buf.len()));
        return Ok(String::from_utf8_lossy(&buf).into_owned());
    }
    Err(Error::in_context(sys::LEP_E_BUFFER, context))
}
