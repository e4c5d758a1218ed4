//! Plain values the session hands out: identity, rated values, samples,
//! events and recordings.

use leptrino_sys as sys;

use crate::ErrorKind;

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
    pub(crate) fn from_axes(a: [f64; 6]) -> Rated {
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
    /// The host low-pass has not settled since the start or a gap.
    pub fn settling(&self) -> bool {
        self.flags & sys::LEP_SF_SETTLING as u8 != 0
    }
    /// An SI value is beyond its limit ([`Control::set_limits`](crate::Control::set_limits)).
    pub fn limit(&self) -> bool {
        self.flags & sys::LEP_SF_LIMIT as u8 != 0
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

/// Something the session noticed beside the data (`lep_session_next_event`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Event {
    /// Where it applies: the number of samples delivered before it, counted
    /// from the start of the recording or iteration it came with (the
    /// library's row of the event in the batch, `LEP_EVF_ROW`, plus the rows
    /// read before that batch); from [`Sensor::take_events`](crate::Sensor::take_events),
    /// counted from the stream's start (`LEP_EVF_SAMPLE`). 0 for an event
    /// from before the stream (an untare while stopped) or the recording.
    pub sample: u64,
    /// When, monotonic seconds.
    pub t: f64,
    /// When, UTC seconds.
    pub t_utc: f64,
    /// What happened.
    pub kind: EventKind,
}

/// Fields of an event, as `lep_session_next_event` fills them.
pub(crate) const EVF_COUNT: usize = sys::LEP_EVF_COUNT as usize;

/// Six fields from index i on.
pub(crate) fn six(f: &[f64], i: u32) -> [f64; 6] {
    let i = i as usize;
    [f[i], f[i + 1], f[i + 2], f[i + 3], f[i + 4], f[i + 5]]
}

/// Three fields from index i on.
pub(crate) fn three(f: &[f64], i: u32) -> [f64; 3] {
    let i = i as usize;
    [f[i], f[i + 1], f[i + 2]]
}

impl Event {
    /// From the fields of `lep_session_next_event` (indices `LEP_EVF_*`):
    /// `sample` the stream's row (`LEP_EVF_SAMPLE`), or with `first` (the
    /// caller's row count before its last read) `first` plus the event's row
    /// in that read's batch (`LEP_EVF_ROW`; one from before the caller's
    /// first row is at 0).
    pub(crate) fn from_fields(f: &[f64; EVF_COUNT], first: Option<u64>) -> Event {
        let at = |i: u32| f[i as usize];
        let error = at(sys::LEP_EVF_ERROR) as i32;
        let cause = ErrorKind::from_code(error).unwrap_or(ErrorKind::Disconnected);
        let axes = at(sys::LEP_EVF_AXES) as u8;
        let status = at(sys::LEP_EVF_STATUS) as u8;
        let (from, to) = (at(sys::LEP_EVF_GAP_FROM), at(sys::LEP_EVF_GAP_TO));
        let type_ = at(sys::LEP_EVF_TYPE) as i32;
        let kind = match u32::try_from(type_).unwrap_or(0) {
            sys::LEP_EV_GAP => EventKind::Gap {
                from,
                to,
                lost: at(sys::LEP_EVF_LOST) as u32,
            },
            sys::LEP_EV_DISCONNECTED => EventKind::Disconnected { cause, last: from },
            sys::LEP_EV_RECONNECTED => EventKind::Reconnected { cause, from, to },
            sys::LEP_EV_TARE => EventKind::Tare {
                offsets: six(f, sys::LEP_EVF_TARE),
            },
            sys::LEP_EV_OVERLOAD_BEGIN => EventKind::OverloadBegin { axes, status },
            sys::LEP_EV_OVERLOAD_END => EventKind::OverloadEnd { axes, status },
            sys::LEP_EV_LIMIT_EXCEEDED => EventKind::LimitExceeded {
                axes,
                wrench: six(f, sys::LEP_EVF_WRENCH),
            },
            sys::LEP_EV_LIMIT_CLEARED => EventKind::LimitCleared {
                wrench: six(f, sys::LEP_EVF_WRENCH),
            },
            _ => EventKind::Other(type_),
        };
        let sample = match first {
            None => at(sys::LEP_EVF_SAMPLE) as u64,
            Some(first) => (first as i64 + at(sys::LEP_EVF_ROW) as i64).max(0) as u64,
        };
        Event {
            sample,
            t: at(sys::LEP_EVF_T_MONO),
            t_utc: at(sys::LEP_EVF_T_UTC),
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

/// Health fields `lep_session_health` fills (`LEP_H_*`).
pub(crate) const H_COUNT: usize = sys::LEP_H_COUNT as usize;

/// The counters of the current connection's client (part of [`Health`]).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct ClientStats {
    /// Framed messages with a good BCC.
    pub messages: u64,
    /// Frames rejected for a BCC mismatch.
    pub bcc_errors: u64,
    /// Frames rejected otherwise (bad escape, too long, restart).
    pub frame_errors: u64,
    /// Received bytes that were not part of a good message or NAK.
    pub bytes_discarded: u64,
    /// DLE NAK received.
    pub naks: u64,
    /// Commands sent again after a NAK.
    pub retries: u64,
    /// Good messages of the wrong type, skipped.
    pub unexpected: u64,
    /// Good frames whose message failed validation.
    pub invalid: u64,
    /// Transactions and blocking reads that timed out.
    pub timeouts: u64,
    /// Stream samples delivered by the client.
    pub samples: u64,
    /// Commands sent again because no answer came in time.
    pub resent_after_timeout: u64,
    /// Resent starts/stops taken as done (their first copy had been executed).
    pub resent_confirmed: u64,
    /// Starts refused because a stream ran, recovered by stop, drain, start.
    pub recoveries: u64,
    /// Data messages whose last reserved byte was not 0.
    pub reserved_nonzero: u64,
    /// Stream watchdog expiries.
    pub stalls: u64,
}

/// Health since the stream started (`lep_session_health`): measured against
/// nominal rate, samples lost, gaps, errors, overloads, reconnects. The named
/// fields are the library's `LEP_H_*`; [`fields`](Self::fields) gives every
/// field by the library's names (a newer library's too).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Health {
    /// From the first sample to the last, s.
    pub elapsed_s: f64,
    /// The nominal rate (the option "nominal-rate", else the sensor's), Hz.
    pub nominal_hz: f64,
    /// (samples received - 1) / elapsed, before decimation, Hz.
    pub measured_hz: f64,
    /// Over the last second or so, Hz.
    pub recent_hz: f64,
    /// Measured below 98 % of nominal over at least 1 s.
    pub shortfall: bool,
    /// Samples received (tare samples included).
    pub received: u64,
    /// Samples delivered (after decimation).
    pub delivered: u64,
    /// Samples estimated lost in gaps.
    pub lost: u64,
    /// Gaps.
    pub gaps: u64,
    /// Framing, BCC, invalid messages, timeouts (all connections).
    pub errors: u64,
    /// Overload episodes begun.
    pub overloads: u64,
    /// Limit episodes begun.
    pub limit_episodes: u64,
    /// Disconnects.
    pub disconnects: u64,
    /// Reconnects.
    pub reconnects: u64,
    /// Events pushed out of the full queue before they were taken.
    pub events_dropped: u64,
    /// The longest gap, s.
    pub max_gap_s: f64,
    /// The current connection's client counters.
    pub client: ClientStats,
    values: [f64; H_COUNT],
}

impl Default for Health {
    fn default() -> Self {
        Health::from_fields(&[0.0; H_COUNT])
    }
}

impl Health {
    pub(crate) fn from_fields(f: &[f64; H_COUNT]) -> Health {
        let d = |i: u32| f[i as usize];
        let n = |i: u32| f[i as usize] as u64;
        Health {
            elapsed_s: d(sys::LEP_H_ELAPSED_S),
            nominal_hz: d(sys::LEP_H_NOMINAL_HZ),
            measured_hz: d(sys::LEP_H_MEASURED_HZ),
            recent_hz: d(sys::LEP_H_RECENT_HZ),
            shortfall: d(sys::LEP_H_SHORTFALL) != 0.0,
            received: n(sys::LEP_H_RECEIVED),
            delivered: n(sys::LEP_H_DELIVERED),
            lost: n(sys::LEP_H_LOST),
            gaps: n(sys::LEP_H_GAPS),
            errors: n(sys::LEP_H_ERRORS),
            overloads: n(sys::LEP_H_OVERLOADS),
            limit_episodes: n(sys::LEP_H_LIMIT_EPISODES),
            disconnects: n(sys::LEP_H_DISCONNECTS),
            reconnects: n(sys::LEP_H_RECONNECTS),
            events_dropped: n(sys::LEP_H_EVENTS_DROPPED),
            max_gap_s: d(sys::LEP_H_MAX_GAP_S),
            client: ClientStats {
                messages: n(sys::LEP_H_MESSAGES),
                bcc_errors: n(sys::LEP_H_BCC_ERRORS),
                frame_errors: n(sys::LEP_H_FRAME_ERRORS),
                bytes_discarded: n(sys::LEP_H_BYTES_DISCARDED),
                naks: n(sys::LEP_H_NAKS),
                retries: n(sys::LEP_H_RETRIES),
                unexpected: n(sys::LEP_H_UNEXPECTED),
                invalid: n(sys::LEP_H_INVALID),
                timeouts: n(sys::LEP_H_TIMEOUTS),
                samples: n(sys::LEP_H_SAMPLES),
                resent_after_timeout: n(sys::LEP_H_RESENT_AFTER_TIMEOUT),
                resent_confirmed: n(sys::LEP_H_RESENT_CONFIRMED),
                recoveries: n(sys::LEP_H_RECOVERIES),
                reserved_nonzero: n(sys::LEP_H_RESERVED_NONZERO),
                stalls: n(sys::LEP_H_STALLS),
            },
            values: *f,
        }
    }

    /// Every field the library fills, by its name ("received",
    /// "bcc_errors", ...: `lep_session_health_field_name`), in its order.
    pub fn fields(&self) -> Vec<(&'static str, f64)> {
        // SAFETY: re-entrant; static names, NULL past the end.
        let n = unsafe { sys::lep_session_health_fields() }.min(H_COUNT);
        (0..n)
            .map(|i| {
                let name =
                    crate::options::static_str(unsafe { sys::lep_session_health_field_name(i) });
                (name, self.values[i])
            })
            .collect()
    }

    /// One field by the library's name; `None` for a name it does not fill.
    pub fn get(&self, name: &str) -> Option<f64> {
        self.fields()
            .into_iter()
            .find(|(n, _)| *n == name)
            .map(|(_, v)| v)
    }
}

/// A tool mounted on the sensor: its mass and centre of mass (sensor frame).
/// A mass of 0 is no payload.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Payload {
    /// Mass, kg (>= 0).
    pub mass_kg: f64,
    /// Centre of mass x, y, z in metres, sensor frame.
    pub com_m: [f64; 3],
}

impl Payload {
    /// A payload of this mass and centre of mass.
    pub fn new(mass_kg: f64, com_m: [f64; 3]) -> Payload {
        Payload { mass_kg, com_m }
    }

    /// The four numbers the option "payload" takes: mass, cx, cy, cz.
    pub fn to_array(&self) -> [f64; 4] {
        let c = self.com_m;
        [self.mass_kg, c[0], c[1], c[2]]
    }

    /// From the four numbers of the option "payload"; `None` for mass 0.
    pub fn from_array(v: [f64; 4]) -> Option<Payload> {
        (v[0] != 0.0).then_some(Payload::new(v[0], [v[1], v[2], v[3]]))
    }
}

/// What a session says about itself (`lep_session_metadata` for the numbers,
/// `lep_session_info` for the texts): every recording's metadata.
#[derive(Debug, Clone, PartialEq)]
pub struct Metadata {
    /// Model, serial, firmware, output-rate field.
    pub product: ProductInfo,
    /// "v1.13 (32-byte info)" or "rate field (38-byte)".
    pub protocol: String,
    /// Rated values.
    pub rated: Rated,
    /// The sensor's filter code, `None` when it refused or did not answer.
    pub sensor_filter: Option<u8>,
    /// The filter's label ("10 Hz"), or "not supported by sensor".
    pub sensor_filter_label: String,
    /// Nominal rate, Hz.
    pub nominal_hz: f64,
    /// Host low-pass cut-off, Hz (0 off).
    pub lowpass_hz: f64,
    /// The host low-pass filter's name, "" when off.
    pub lowpass_name: String,
    /// Its group delay at low frequency, s.
    pub lowpass_delay_s: f64,
    /// Every nth sample delivered.
    pub decimate: u32,
    /// Output rotation, row-major.
    pub rotation: [f64; 9],
    /// Moment reference point, m.
    pub shift_m: [f64; 3],
    /// A tare is in force.
    pub tared: bool,
    /// The tare offsets, counts.
    pub tare: [f64; 6],
    /// UTC s of the last start (of the open before one).
    pub start_utc: f64,
    /// Monotonic s of the same instant.
    pub start_mono: f64,
    /// The port's path.
    pub port: String,
    /// An in-process virtual sensor.
    pub sim: bool,
    /// The library's version.
    pub library_version: String,
    /// The payload compensated, if any.
    pub payload: Option<Payload>,
    /// Gravity in the sensor frame, m/s².
    pub gravity: [f64; 3],
    /// Limits per axis, N and N·m (0: none).
    pub limit: [f64; 6],
}

/// Metadata fields `lep_session_metadata` fills (`LEP_MD_*`).
pub(crate) const MD_COUNT: usize = sys::LEP_MD_COUNT as usize;

/// The numbers of `lep_session_metadata`, indexed by `LEP_MD_*`.
pub(crate) struct MetaNumbers(pub(crate) [f64; MD_COUNT]);

impl MetaNumbers {
    pub(crate) fn at(&self, i: u32) -> f64 {
        self.0[i as usize]
    }
    pub(crate) fn rated(&self) -> Rated {
        Rated::from_axes(six(&self.0, sys::LEP_MD_RATED))
    }
    pub(crate) fn output_rate_hz(&self) -> Option<u32> {
        let r = self.at(sys::LEP_MD_OUTPUT_RATE_HZ);
        (r > 0.0).then_some(r as u32)
    }
    pub(crate) fn sensor_filter(&self) -> Option<u8> {
        let f = self.at(sys::LEP_MD_SENSOR_FILTER);
        (f >= 0.0).then_some(f as u8)
    }
    pub(crate) fn nominal_hz(&self) -> f64 {
        self.at(sys::LEP_MD_NOMINAL_HZ)
    }
    pub(crate) fn start_mono(&self) -> f64 {
        self.at(sys::LEP_MD_START_MONO)
    }
    pub(crate) fn payload(&self) -> Option<Payload> {
        let i = sys::LEP_MD_PAYLOAD as usize;
        Payload::from_array([self.0[i], self.0[i + 1], self.0[i + 2], self.0[i + 3]])
    }
    pub(crate) fn rotation(&self) -> [f64; 9] {
        let i = sys::LEP_MD_ROTATION as usize;
        let mut r = [0.0; 9];
        r.copy_from_slice(&self.0[i..i + 9]);
        r
    }
}

/// A serial port found on this machine ([`list_ports`](crate::list_ports)).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PortInfo {
    /// The device path (/dev/ttyACM0).
    pub path: String,
    /// A stable path (/dev/serial/by-id/...), or "".
    pub by_id: String,
    /// The USB product/manufacturer when known, or "".
    pub description: String,
    /// USB vendor id, 0 when unknown.
    pub vid: u16,
    /// USB product id, 0 when unknown.
    pub pid: u16,
    /// Likely a sensor (STM VCP 0483:5740 or FTDI 0403:6001).
    pub likely_sensor: bool,
}

// The session's [cap*6] columns are read as rows of six.
const _: () = assert!(sys::LEP_AXES == 6);
