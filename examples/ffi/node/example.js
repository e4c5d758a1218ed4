// leptrino from Node through koffi: what the README's C example does, against
// the in-process virtual sensor (option "sim" = 1), with only handles, numbers,
// typed arrays, buffers and strings crossing the boundary: no struct declared,
// no layout mirrored (docs/ffi.md).
//
// Run: npm ci && LEPTRINO_LIB=/path/to/libleptrino.so node example.js
// (without LEPTRINO_LIB the loader's path is searched for libleptrino.so).
'use strict';

const koffi = require('koffi');

const libPath = process.env.LEPTRINO_LIB || 'libleptrino.so';
let lib;
try {
  lib = koffi.load(libPath);
} catch (e) {
  console.error(`leptrino-ffi-node: cannot load ${libPath} (set LEPTRINO_LIB): ${e.message}`);
  process.exit(1);
}

// Handles are opaque: only pointers to them cross.
koffi.opaque('lep_options');
koffi.opaque('lep_session');

// The functions used, declared from include/leptrino/*.h. Arrays the library
// fills are Float64Array / Buffer arguments, filled in place; `_Out_` marks
// a pointer to one value that koffi copies back into a one-element array.
const C = {
  lep_version: lib.func('const char *lep_version(void)'),
  lep_strerror: lib.func('const char *lep_strerror(int err)'),
  lep_options_new: lib.func('lep_options *lep_options_new(void)'),
  lep_options_free: lib.func('void lep_options_free(lep_options *o)'),
  lep_options_set: lib.func(
    'int lep_options_set(lep_options *o, const char *name, const char *value, char *err, size_t errlen)'),
  lep_options_set_int: lib.func(
    'int lep_options_set_int(lep_options *o, const char *name, int64_t value, char *err, size_t errlen)'),
  lep_session_open: lib.func(
    'int lep_session_open(const lep_options *o, _Out_ lep_session **out, char *err, size_t errlen)'),
  lep_session_close: lib.func('void lep_session_close(lep_session *s)'),
  lep_session_start: lib.func('int lep_session_start(lep_session *s)'),
  lep_session_stop: lib.func('int lep_session_stop(lep_session *s)'),
  lep_session_read: lib.func(
    'int lep_session_read(lep_session *s, int timeout_ms, size_t cap, _Out_ size_t *n, ' +
    'double *t_mono, double *t_utc, double *si, int16_t *raw, double *zeroed, ' +
    'uint8_t *status, uint8_t *flags, uint16_t *seq)'),
  lep_session_event_fields: lib.func('size_t lep_session_event_fields(void)'),
  lep_session_next_event: lib.func(
    'int lep_session_next_event(lep_session *s, double *fields, size_t nfields)'),
  lep_session_tare: lib.func('int lep_session_tare(lep_session *s, int samples, double duration_s)'),
  lep_session_info: lib.func(
    'int lep_session_info(lep_session *s, int which, char *buf, size_t cap, _Out_ size_t *len)'),
  lep_session_rated: lib.func('int lep_session_rated(lep_session *s, double *rated)'),
  lep_session_health_fields: lib.func('size_t lep_session_health_fields(void)'),
  lep_session_health: lib.func('int lep_session_health(lep_session *s, double *out, size_t n)'),
};

// Enumerators of the headers (values never change: docs/ffi.md, evolution).
const LEP_OK = 0;
const LEP_E_BUFFER = -2;
const LEP_INFO_MODEL = 0, LEP_INFO_SERIAL = 1, LEP_INFO_FIRMWARE = 2;
const LEP_EVF_TYPE = 0;
const LEP_EV_TARE = 4;
const LEP_H_NOMINAL_HZ = 1, LEP_H_MEASURED_HZ = 2;
const FZ = 2; // Fx Fy Fz Mx My Mz

// The NUL-terminated UTF-8 text at the start of buf.
function text(buf) {
  const end = buf.indexOf(0);
  return buf.toString('utf8', 0, end < 0 ? buf.length : end);
}

function check(what, rc, err) {
  if (rc === LEP_OK) return;
  const msg = err ? text(err) : '';
  throw new Error(`${what}: ${msg ? msg + ' ' : ''}(${C.lep_strerror(rc)})`);
}

// Ask how long the text is (buf null, cap 0), then fetch it.
function info(s, which) {
  const len = [0];
  const rc = C.lep_session_info(s, which, null, 0, len);
  if (rc !== LEP_OK && rc !== LEP_E_BUFFER) check('lep_session_info', rc);
  const buf = Buffer.alloc(Number(len[0]) + 1);
  check('lep_session_info', C.lep_session_info(s, which, buf, buf.length, len));
  return text(buf);
}

// Reads samples into typed arrays reused from call to call.
class Reader {
  constructor(s, capacity) {
    this.s = s;
    this.tMono = new Float64Array(capacity);
    this.si = new Float64Array(capacity * 6); // [n*6]: Fx Fy Fz Mx My Mz
  }

  // One call: how many samples are in tMono and si.
  read() {
    const n = [0];
    const rc = C.lep_session_read(this.s, 1000, this.tMono.length, n, this.tMono, null, this.si,
      null, null, null, null, null);
    check('lep_session_read', rc);
    return Number(n[0]);
  }
}

function session(s) {
  // Identity and rated values.
  const model = info(s, LEP_INFO_MODEL);
  console.log(`sensor ${model} serial ${info(s, LEP_INFO_SERIAL)} firmware ${info(s, LEP_INFO_FIRMWARE)}`);
  const rated = new Float64Array(6);
  check('lep_session_rated', C.lep_session_rated(s, rated));
  console.log(`rated Fx ${rated[0]} Fy ${rated[1]} Fz ${rated[2]} N, ` +
    `Mx ${rated[3]} My ${rated[4]} Mz ${rated[5]} N m`);
  if (!model || !(rated[FZ] > 0)) throw new Error('no identity or rated values');

  // One second of samples.
  check('lep_session_start', C.lep_session_start(s));
  const r = new Reader(s, 256);
  let count = 0, t0 = NaN, tLast = 0, sumFz = 0;
  for (let done = false; !done;) {
    const n = r.read();
    for (let i = 0; i < n; i++) {
      if (Number.isNaN(t0)) t0 = r.tMono[i];
      if (r.tMono[i] - t0 >= 1.0) {
        done = true;
        break;
      }
      count++;
      tLast = r.tMono[i];
      sumFz += r.si[i * 6 + FZ];
    }
  }
  const rate = (count - 1) / (tLast - t0);
  const health = new Float64Array(Number(C.lep_session_health_fields()));
  check('lep_session_health', C.lep_session_health(s, health, health.length));
  const nominal = health[LEP_H_NOMINAL_HZ];
  console.log(`1 s: ${count} samples, ${rate.toFixed(1)} Hz measured ` +
    `(library: ${health[LEP_H_MEASURED_HZ].toFixed(1)} Hz, nominal ${nominal.toFixed(0)} Hz)`);
  if (count < 100 || rate < 0.5 * nominal || rate > 1.5 * nominal) throw new Error('the rate is off');
  const before = sumFz / count;

  // Tare: average 100 samples, then wait for the LEP_EV_TARE event.
  check('lep_session_tare', C.lep_session_tare(s, 100, 0));
  const fields = new Float64Array(Number(C.lep_session_event_fields()));
  let tared = false;
  for (let tries = 0; !tared && tries < 100; tries++) {
    r.read();
    while (!tared && C.lep_session_next_event(s, fields, fields.length) === 1) {
      tared = fields[LEP_EVF_TYPE] === LEP_EV_TARE;
    }
  }
  if (!tared) throw new Error('no tare event');
  let n = 0, sum = 0;
  while (n < 240) {
    const got = r.read();
    for (let i = 0; i < got; i++) sum += r.si[i * 6 + FZ];
    n += got;
  }
  const after = sum / n;
  console.log(`mean Fz ${before.toFixed(3)} N before the tare, ${after.toFixed(3)} N after (${n} samples)`);
  if (Math.abs(before) < 0.01 * rated[FZ] || Math.abs(after) > 0.005 * rated[FZ]) {
    throw new Error('the tare did not zero Fz');
  }
  check('lep_session_stop', C.lep_session_stop(s));
}

// A port that does not exist: the library's message and lep_strerror.
function missingPort(err) {
  const bad = C.lep_options_new();
  try {
    check('option port', C.lep_options_set(bad, 'port', '/dev/does-not-exist', err, err.length), err);
    const out = [null];
    const rc = C.lep_session_open(bad, out, err, err.length);
    if (rc === LEP_OK || out[0]) {
      C.lep_session_close(out[0]);
      throw new Error('opening /dev/does-not-exist succeeded');
    }
    console.log(`missing port: ${text(err)} (${rc}: ${C.lep_strerror(rc)})`);
  } finally {
    C.lep_options_free(bad);
  }
}

function main() {
  console.log(`leptrino ${C.lep_version()} from Node (koffi ${koffi.version})`);
  const err = Buffer.alloc(256);
  const o = C.lep_options_new();
  if (!o) throw new Error('lep_options_new: out of memory');
  let s;
  try {
    check('option sim', C.lep_options_set_int(o, 'sim', 1, err, err.length), err);
    // a constant load, no noise: the tare visibly zeroes it
    check('option sim-constant', C.lep_options_set_int(o, 'sim-constant', 1, err, err.length), err);
    const out = [null];
    check('lep_session_open', C.lep_session_open(o, out, err, err.length), err);
    s = out[0];
  } finally {
    C.lep_options_free(o); // the session copied what it needs
  }
  try {
    session(s);
  } finally {
    C.lep_session_close(s);
  }
  missingPort(err);
  console.log('ok');
}

try {
  main();
} catch (e) {
  console.error(`leptrino-ffi-node: ${e.message}`);
  process.exit(1);
}
