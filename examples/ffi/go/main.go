// leptrino from Go through cgo: what the README's C example does, against the
// in-process virtual sensor (option "sim" = 1), with only handles, numbers,
// flat arrays and strings crossing the boundary (docs/ffi.md).
//
// Build and run against an installed leptrino (pkg-config finds it):
//
//	PKG_CONFIG_PATH=$PREFIX/lib/pkgconfig go build -o leptrino-ffi-go .
//	LD_LIBRARY_PATH=$PREFIX/lib ./leptrino-ffi-go
//
// Arrays are Go slices passed as &slice[0]: they hold no Go pointers, so cgo's
// pointer rules allow it, and the library keeps none of them after a call.
package main

/*
#cgo pkg-config: leptrino
#include <stdlib.h>
#include <leptrino/leptrino.h>
#include <leptrino/options.h>
#include <leptrino/session.h>
*/
import "C"

import (
	"fmt"
	"math"
	"os"
	"unsafe"
)

const errLen = 256

// lepError is a LEP_E_* code with the library's one-line message, if any.
type lepError struct {
	what string
	code C.int
	msg  string
}

func (e *lepError) Error() string {
	if e.msg != "" {
		return fmt.Sprintf("%s: %s (%s)", e.what, e.msg, C.GoString(C.lep_strerror(e.code)))
	}
	return fmt.Sprintf("%s: %s", e.what, C.GoString(C.lep_strerror(e.code)))
}

func check(what string, rc C.int, err []byte) error {
	if rc == C.LEP_OK {
		return nil
	}
	e := &lepError{what: what, code: rc}
	if err != nil {
		e.msg = cstr(err)
	}
	return e
}

// cstr is the NUL-terminated text at the start of buf.
func cstr(buf []byte) string {
	for i, b := range buf {
		if b == 0 {
			return string(buf[:i])
		}
	}
	return string(buf)
}

func charp(buf []byte) *C.char        { return (*C.char)(unsafe.Pointer(&buf[0])) }
func doublep(buf []float64) *C.double { return (*C.double)(unsafe.Pointer(&buf[0])) }

func setInt(o *C.lep_options, name string, v int64) error {
	cname := C.CString(name)
	defer C.free(unsafe.Pointer(cname))
	err := make([]byte, errLen)
	rc := C.lep_options_set_int(o, cname, C.int64_t(v), charp(err), C.size_t(len(err)))
	return check("option "+name, rc, err)
}

func setText(o *C.lep_options, name, value string) error {
	cname, cvalue := C.CString(name), C.CString(value)
	defer C.free(unsafe.Pointer(cname))
	defer C.free(unsafe.Pointer(cvalue))
	err := make([]byte, errLen)
	rc := C.lep_options_set(o, cname, cvalue, charp(err), C.size_t(len(err)))
	return check("option "+name, rc, err)
}

// info asks how long the text is (buf NULL, cap 0), then fetches it.
func info(s *C.lep_session, which C.int) (string, error) {
	var n C.size_t
	rc := C.lep_session_info(s, which, nil, 0, &n)
	if rc != C.LEP_OK && rc != C.LEP_E_BUFFER {
		return "", check("lep_session_info", rc, nil)
	}
	buf := make([]byte, int(n)+1)
	rc = C.lep_session_info(s, which, charp(buf), C.size_t(len(buf)), &n)
	if err := check("lep_session_info", rc, nil); err != nil {
		return "", err
	}
	return string(buf[:n]), nil
}

// reader reads samples into Go slices reused from call to call.
type reader struct {
	s     *C.lep_session
	tMono []float64
	si    []float64 // [n*6]: Fx Fy Fz Mx My Mz
}

func newReader(s *C.lep_session, capacity int) *reader {
	return &reader{s: s, tMono: make([]float64, capacity), si: make([]float64, capacity*6)}
}

// read returns the samples of one call (slices valid until the next call).
func (r *reader) read() (tMono, si []float64, err error) {
	var n C.size_t
	rc := C.lep_session_read(r.s, 1000, C.size_t(len(r.tMono)), &n, doublep(r.tMono), nil,
		doublep(r.si), nil, nil, nil, nil, nil)
	if rc != C.LEP_OK {
		return nil, nil, check("lep_session_read", rc, nil)
	}
	return r.tMono[:n], r.si[:n*6], nil
}

func run() error {
	fmt.Printf("leptrino %s from Go (cgo)\n", C.GoString(C.lep_version()))

	o := C.lep_options_new()
	if o == nil {
		return fmt.Errorf("lep_options_new: out of memory")
	}
	defer C.lep_options_free(o)
	if err := setInt(o, "sim", 1); err != nil {
		return err
	}
	if err := setInt(o, "sim-constant", 1); err != nil { // a constant load, no noise
		return err
	}
	var s *C.lep_session
	err := make([]byte, errLen)
	if e := check("lep_session_open", C.lep_session_open(o, &s, charp(err), C.size_t(len(err))), err); e != nil {
		return e
	}
	defer C.lep_session_close(s)

	// Identity and rated values.
	var text [3]string
	for i, which := range []C.int{C.LEP_INFO_MODEL, C.LEP_INFO_SERIAL, C.LEP_INFO_FIRMWARE} {
		t, e := info(s, which)
		if e != nil {
			return e
		}
		text[i] = t
	}
	fmt.Printf("sensor %s serial %s firmware %s\n", text[0], text[1], text[2])
	rated := make([]float64, 6)
	if e := check("lep_session_rated", C.lep_session_rated(s, doublep(rated)), nil); e != nil {
		return e
	}
	fmt.Printf("rated Fx %g Fy %g Fz %g N, Mx %g My %g Mz %g N m\n",
		rated[0], rated[1], rated[2], rated[3], rated[4], rated[5])
	if text[0] == "" || rated[2] <= 0 {
		return fmt.Errorf("no identity or rated values")
	}

	// One second of samples.
	if e := check("lep_session_start", C.lep_session_start(s), nil); e != nil {
		return e
	}
	r := newReader(s, 256)
	count, t0, tLast, sumFz := 0, math.NaN(), 0.0, 0.0
	for done := false; !done; {
		tm, si, e := r.read()
		if e != nil {
			return e
		}
		for i, t := range tm {
			if math.IsNaN(t0) {
				t0 = t
			}
			if t-t0 >= 1.0 {
				done = true
				break
			}
			count++
			tLast = t
			sumFz += si[i*6+2]
		}
	}
	rate := float64(count-1) / (tLast - t0)
	health := make([]float64, int(C.lep_session_health_fields()))
	if e := check("lep_session_health", C.lep_session_health(s, doublep(health), C.size_t(len(health))), nil); e != nil {
		return e
	}
	fmt.Printf("1 s: %d samples, %.1f Hz measured (library: %.1f Hz, nominal %.0f Hz)\n",
		count, rate, health[C.LEP_H_MEASURED_HZ], health[C.LEP_H_NOMINAL_HZ])
	if count < 100 || rate < 0.5*health[C.LEP_H_NOMINAL_HZ] || rate > 1.5*health[C.LEP_H_NOMINAL_HZ] {
		return fmt.Errorf("the rate is off")
	}
	before := sumFz / float64(count)

	// Tare: average 100 samples, then wait for the LEP_EV_TARE event.
	if e := check("lep_session_tare", C.lep_session_tare(s, 100, 0), nil); e != nil {
		return e
	}
	fields := make([]float64, int(C.lep_session_event_fields()))
	tared := false
	for tries := 0; !tared && tries < 100; tries++ {
		if _, _, e := r.read(); e != nil {
			return e
		}
		for !tared && C.lep_session_next_event(s, doublep(fields), C.size_t(len(fields))) == 1 {
			tared = fields[C.LEP_EVF_TYPE] == C.LEP_EV_TARE
		}
	}
	if !tared {
		return fmt.Errorf("no tare event")
	}
	n, sum := 0, 0.0
	for n < 240 {
		_, si, e := r.read()
		if e != nil {
			return e
		}
		for i := 0; i*6 < len(si); i++ {
			sum += si[i*6+2]
			n++
		}
	}
	after := sum / float64(n)
	fmt.Printf("mean Fz %.3f N before the tare, %.3f N after (%d samples)\n", before, after, n)
	if math.Abs(before) < 0.01*rated[2] || math.Abs(after) > 0.005*rated[2] {
		return fmt.Errorf("the tare did not zero Fz")
	}
	if e := check("lep_session_stop", C.lep_session_stop(s), nil); e != nil {
		return e
	}

	// A port that does not exist: the library's message and lep_strerror.
	bad := C.lep_options_new()
	defer C.lep_options_free(bad)
	if e := setText(bad, "port", "/dev/does-not-exist"); e != nil {
		return e
	}
	var none *C.lep_session
	rc := C.lep_session_open(bad, &none, charp(err), C.size_t(len(err)))
	if rc == C.LEP_OK || none != nil {
		C.lep_session_close(none)
		return fmt.Errorf("opening /dev/does-not-exist succeeded")
	}
	fmt.Printf("missing port: %s (%d: %s)\n", cstr(err), int(rc), C.GoString(C.lep_strerror(rc)))
	return nil
}

func main() {
	if err := run(); err != nil {
		fmt.Fprintln(os.Stderr, "leptrino-ffi-go:", err)
		os.Exit(1)
	}
	fmt.Println("ok")
}
