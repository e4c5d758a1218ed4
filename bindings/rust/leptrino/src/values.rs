//! Plain values the session hands out: identity, rated values, samples,
//! events and recordings.

use std::ffi::c_char;

use leptrino_sys as sys;

use crate::ErrorKind;

fn text(field: &[c_char]) -> String {
    // SAFETY: the library NUL-terminates every text field of these structs;
    // the slice bounds the read should it not.
    let bytes: &[u8] = unsafe { std::slice::from_raw_parts(field.as_ptr().cast(), field.len()) };
    let end = bytes.iter().position(|&b| b == 0).unwrap_or(bytes.len());
    String::from_utf8_lossy(&bytes[..end]).into_owned()
}

/// What the sensor says it is (product information, command 0x2A), read when
/// it was opened.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ProductInfo {
    /// e.g. "PFS055YA501U6"
    pub model: String,
    /// e.g. "00000001"
    pub serial: String,
    /// e.g. "1.13"
    pub firmware: String,
    /// The output-rate field of the 38-byte form, when the sensor sends it
    /// and it is a number.
    pub output_rate_hz: Option<u32>,
}

impl ProductInfo {
    pub(crate) fn from_c(c: &sys::lep_product_info) -> ProductInfo {
        ProductInfo {
            model: text(&c.model),
            serial: text(&c.serial),
            firmware: text(&c.firmware),
            output_rate_hz: (c.has_output_rate != 0 && c.output_rate_hz > 0)
                .then_some(c.output_rate_hz),
        }
    }
}

/// Rated (full-scale) values (command 0x2B): force in N, torque in N·m.
/// Raw counts of ±10000 are ± these.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rated {
    /// Fx, Fy, Fz in N
    pub force: [f64; 3],
    /// Mx, My, Mz in N·m
    pub torque: [f64; 3],
}

impl Rated {
    pub(crate) fn from_c(c: &sys::lep_rated) -> Rated {
        let a = c.axis.map(f64::from);
        Rated {
            force: [a[0], a[1], a[2]],
            torque: [a[3], a[4], a[5]],
        }
    }

    /// The six axes in order Fx Fy Fz Mx My Mz.
    pub fn axes(&self) -> [f64; 6] {
        let (f, m) = (self.force, self.torque);
        [f[0], f[1], f[2], m[0], m[1], m[2]]
    }
}

/// One sample.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    /// Arrival, seconds of the library's monotonic clock (`lep_monotonic_seconds`).
    pub t: f64,
    /// The same instant, seconds since 1970-01-01 UTC.
    pub t_utc: f64,
    /// Counts as received (±10000 = ± rated).
    pub raw: [i16; 6],
    /// Raw minus the tare offsets, counts.
    pub zeroed: [f64; 6],
    /// N and N·m: Fx Fy Fz Mx My Mz (tare, host low-pass, decimation,
    /// rotation and moment-point shift applied, as the session does).
    pub si: [f64; 6],
    /// The sensor's status bits (`LEP_STATUS_*`).
    pub status: u8,
    /// The session's flags (`LEP_SF_*`): see [`gap`](Self::gap) and the others.
    pub flags: u8,
    /// The reserved bytes: the virtual sensor's sequence number.
    pub seq: u16,
}

impl Sample {
    /// Fx, Fy, Fz in N.
    pub fn force(&self) -> [f64; 3] {
        [self.si[0], self.si[1], self.si[2]]
    }
    /// Mx, My, Mz in N·m.
    pub fn torque(&self) -> [f64; 3] {
        [self.si[3], self.si[4], self.si[5]]
    }
    /// A gap (lost samples, a disconnect) lies just before this sample.
    pub fn gap(&self) -> bool {
        self.flags & sys::LEP_SF_GAP as u8 != 0
    }
    /// Overload status bit, or an axis at saturation.
    pub fn overload(&self) -> bool {
        self.flags & sys::LEP_SF_OVERLOAD as u8 != 0
    }
    /// A tare is averaging this sample.
    pub fn taring(&self) -> bool {
        self.flags & sys::LEP_SF_TARING as u8 != 0
    }
}

/// What happened, in an [`Event`].
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum EventKind {
    /// A hole in the data (lost samples, a stall, a stolen read).
    Gap {
        /// Arrival of the last sample before it, monotonic s.
        from: f64,
        /// Arrival of the first sample after it, monotonic s.
        to: f64,
        /// Samples estimated lost (exact from the virtual sensor's sequence numbers).
        lost: u32,
    },
    /// The port went away or the data timed out.
    Disconnected {
        /// `ErrorKind::Disconnected` or `ErrorKind::Timeout`.
        cause: ErrorKind,
        /// Arrival of the last sample received, monotonic s.
        last: f64,
    },
    /// The stream runs again after a disconnect (with `reconnect`).
    Reconnected {
        /// What caused the loss: `Disconnected` or `Timeout`.
        cause: ErrorKind,
        /// Arrival of the last sample before the loss, monotonic s.
        from: f64,
        /// Arrival of the first sample after it, monotonic s.
        to: f64,
    },
    /// The tare offsets changed.
    Tare {
        /// The offsets now in force, counts (zeros when untared).
        offsets: [f64; 6],
    },
    /// An overload began.
    OverloadBegin {
        /// Bit i set: axis i saturated.
        axes: u8,
        /// The sensor's status bits.
        status: u8,
    },
    /// The overload ended.
    OverloadEnd {
        /// Bit i set: axis i saturated.
        axes: u8,
        /// The sensor's status bits.
        status: u8,
    },
    /// An SI value went beyond its limit (set with the session's limits).
    LimitExceeded {
        /// Bit i set: axis i beyond its limit.
        axes: u8,
        /// The sample's SI values, N and N·m.
        wrench: [f64; 6],
    },
    /// Every SI value is back within 95 % of its limit.
    LimitCleared {
        /// The sample's SI values, N and N·m.
        wrench: [f64; 6],
    },
    /// An event type this crate does not know (a newer library).
    Other(i32),
}

/// Something the session noticed beside the data (`lep_session_event`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Event {
    /// Where it applies: the number of samples delivered before it, counted
    /// from the start of the recording or iteration it came with.
    pub sample: u64,
    /// When, monotonic seconds.
    pub t: f64,
    /// When, UTC seconds.
    pub t_utc: f64,
    /// What happened.
    pub kind: EventKind,
}

impl Event {
    pub(crate) fn from_c(e: &sys::lep_session_event, base: u64, start_mono: f64) -> Event {
        let cause = ErrorKind::from_code(e.error).unwrap_or(ErrorKind::Disconnected);
        let kind = match e.type_ as u32 {
            sys::LEP_EV_GAP => EventKind::Gap {
                from: e.gap_from,
                to: e.gap_to,
                lost: e.lost,
            },
            sys::LEP_EV_DISCONNECTED => EventKind::Disconnected {
                cause,
                last: e.gap_from,
            },
            sys::LEP_EV_RECONNECTED => EventKind::Reconnected {
                cause,
                from: e.gap_from,
                to: e.gap_to,
            },
            sys::LEP_EV_TARE => EventKind::Tare { offsets: e.tare },
            sys::LEP_EV_OVERLOAD_BEGIN => EventKind::OverloadBegin {
                axes: e.axes,
                status: e.status,
            },
            sys::LEP_EV_OVERLOAD_END => EventKind::OverloadEnd {
                axes: e.axes,
                status: e.status,
            },
            sys::LEP_EV_LIMIT_EXCEEDED => EventKind::LimitExceeded {
                axes: e.axes,
                wrench: e.wrench,
            },
            sys::LEP_EV_LIMIT_CLEARED => EventKind::LimitCleared { wrench: e.wrench },
            _ => EventKind::Other(e.type_),
        };
        // queued before this stream started (an untare while stopped): at its start
        let sample = if e.t_mono >= start_mono {
            e.sample.saturating_sub(base)
        } else {
            0
        };
        Event {
            sample,
            t: e.t_mono,
            t_utc: e.t_utc,
            kind,
        }
    }
}

/// Samples recorded by [`Sensor::record`](crate::Sensor::record): one plain
/// vector per column, all of [`len`](Self::len) rows, and the events.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Recording {
    /// Arrival, monotonic seconds.
    pub t: Vec<f64>,
    /// Arrival, UTC seconds.
    pub t_utc: Vec<f64>,
    /// Counts as received.
    pub raw: Vec<[i16; 6]>,
    /// Raw minus the tare offsets, counts.
    pub zeroed: Vec<[f64; 6]>,
    /// Force (N) and torque (N·m): Fx Fy Fz Mx My Mz.
    pub si: Vec<[f64; 6]>,
    /// The sensor's status bits.
    pub status: Vec<u8>,
    /// The session's `LEP_SF_*` flags.
    pub flags: Vec<u8>,
    /// Sequence numbers (the virtual sensor's; the reserved bytes).
    pub seq: Vec<u16>,
    /// Gaps, disconnects, reconnects, tare changes, overloads.
    pub events: Vec<Event>,
    /// The session's metadata, one JSON object (model, serial, rated, filters,
    /// tare, frame, start time); empty when the sensor was gone.
    pub metadata_json: String,
}

impl Recording {
    pub(crate) fn with_capacity(cap: usize) -> Recording {
        Recording {
            t: Vec::with_capacity(cap),
            t_utc: Vec::with_capacity(cap),
            raw: Vec::with_capacity(cap),
            zeroed: Vec::with_capacity(cap),
            si: Vec::with_capacity(cap),
            status: Vec::with_capacity(cap),
            flags: Vec::with_capacity(cap),
            seq: Vec::with_capacity(cap),
            ..Recording::default()
        }
    }

    /// Rows.
    pub fn len(&self) -> usize {
        self.t.len()
    }

    /// No rows.
    pub fn is_empty(&self) -> bool {
        self.t.is_empty()
    }

    /// Fx, Fy, Fz of row i, N.
    pub fn force(&self, i: usize) -> [f64; 3] {
        let s = &self.si[i];
        [s[0], s[1], s[2]]
    }

    /// Mx, My, Mz of row i, N·m.
    pub fn torque(&self, i: usize) -> [f64; 3] {
        let s = &self.si[i];
        [s[3], s[4], s[5]]
    }

    /// Row i as a [`Sample`].
    pub fn sample(&self, i: usize) -> Sample {
        Sample {
            t: self.t[i],
            t_utc: self.t_utc[i],
            raw: self.raw[i],
            zeroed: self.zeroed[i],
            si: self.si[i],
            status: self.status[i],
            flags: self.flags[i],
            seq: self.seq[i],
        }
    }

    /// Samples lost between the first row and the last, counted from the
    /// sequence numbers (meaningful with the virtual sensor, which numbers them).
    pub fn missing(&self) -> u64 {
        self.seq
            .windows(2)
            .map(|w| u64::from(w[1].wrapping_sub(w[0])).saturating_sub(1))
            .sum()
    }

    /// Rows the session flagged with a gap before them.
    pub fn gaps(&self) -> usize {
        self.flags
            .iter()
            .filter(|&&f| f & sys::LEP_SF_GAP as u8 != 0)
            .count()
    }
}

// The session's [cap*6] columns are read as rows of six.
const _: () = assert!(sys::LEP_AXES == 6);
