// leptrino from Java through JNA: what the README's C example does, against the
// in-process virtual sensor (option "sim" = 1), with only handles (Pointer),
// numbers, Java arrays and strings crossing the boundary: no Structure, no
// layout mirrored (docs/ffi.md).
//
// Run: LEPTRINO_LIB=/path/to/libleptrino.so mvn -q -B compile exec:exec
// (without LEPTRINO_LIB, JNA looks for libleptrino.so on the loader's path).
package leptrino.example;

import com.sun.jna.IntegerType;
import com.sun.jna.Library;
import com.sun.jna.Native;
import com.sun.jna.Pointer;
import com.sun.jna.ptr.ByReference;
import com.sun.jna.ptr.PointerByReference;
import java.nio.charset.StandardCharsets;
import java.util.Map;

public final class Example {
    /** C size_t: as wide as the platform's (JNA has no built-in mapping for it). */
    public static final class SizeT extends IntegerType {
        public SizeT() {
            this(0);
        }

        public SizeT(long value) {
            super(Native.SIZE_T_SIZE, value, true);
        }
    }

    /** A size_t that the callee writes (size_t *). */
    public static final class SizeTByReference extends ByReference {
        public SizeTByReference() {
            super(Native.SIZE_T_SIZE);
            if (Native.SIZE_T_SIZE == 8) {
                getPointer().setLong(0, 0);
            } else {
                getPointer().setInt(0, 0);
            }
        }

        public long value() {
            Pointer p = getPointer();
            return Native.SIZE_T_SIZE == 8 ? p.getLong(0) : p.getInt(0) & 0xffffffffL;
        }
    }

    /** The functions used, declared from include/leptrino/*.h. */
    public interface Leptrino extends Library {
        String lep_version();

        String lep_strerror(int err);

        Pointer lep_options_new();

        void lep_options_free(Pointer o);

        int lep_options_set(Pointer o, String name, String value, byte[] err, SizeT errlen);

        int lep_options_set_int(Pointer o, String name, long value, byte[] err, SizeT errlen);

        int lep_session_open(Pointer o, PointerByReference out, byte[] err, SizeT errlen);

        void lep_session_close(Pointer s);

        int lep_session_start(Pointer s);

        int lep_session_stop(Pointer s);

        int lep_session_read(Pointer s, int timeoutMs, SizeT cap, SizeTByReference n,
                double[] tMono, double[] tUtc, double[] si, short[] raw, double[] zeroed,
                byte[] status, byte[] flags, short[] seq);

        SizeT lep_session_event_fields();

        int lep_session_next_event(Pointer s, double[] fields, SizeT nfields);

        int lep_session_tare(Pointer s, int samples, double durationS);

        int lep_session_info(Pointer s, int which, byte[] buf, SizeT cap, SizeTByReference len);

        int lep_session_rated(Pointer s, double[] rated);

        SizeT lep_session_health_fields();

        int lep_session_health(Pointer s, double[] out, SizeT n);
    }

    // Enumerators of the headers (values never change: docs/ffi.md, evolution).
    static final int LEP_OK = 0;
    static final int LEP_E_BUFFER = -2;
    static final int LEP_INFO_MODEL = 0, LEP_INFO_SERIAL = 1, LEP_INFO_FIRMWARE = 2;
    static final int LEP_EVF_TYPE = 0;
    static final int LEP_EV_TARE = 4;
    static final int LEP_H_NOMINAL_HZ = 1, LEP_H_MEASURED_HZ = 2;
    static final int FZ = 2; // Fx Fy Fz Mx My Mz

    static Leptrino lib;

    static final class LepException extends Exception {
        LepException(String message) {
            super(message);
        }
    }

    /** The NUL-terminated UTF-8 text at the start of buf. */
    static String text(byte[] buf) {
        int n = 0;
        while (n < buf.length && buf[n] != 0) {
            n++;
        }
        return new String(buf, 0, n, StandardCharsets.UTF_8);
    }

    static void check(String what, int rc, byte[] err) throws LepException {
        if (rc == LEP_OK) {
            return;
        }
        String msg = err != null ? text(err) : "";
        throw new LepException(what + ": " + (msg.isEmpty() ? "" : msg + " ")
                + "(" + lib.lep_strerror(rc) + ")");
    }

    /** Ask how long the text is (buf null, cap 0), then fetch it. */
    static String info(Pointer s, int which) throws LepException {
        SizeTByReference len = new SizeTByReference();
        int rc = lib.lep_session_info(s, which, null, new SizeT(0), len);
        if (rc != LEP_OK && rc != LEP_E_BUFFER) {
            check("lep_session_info", rc, null);
        }
        byte[] buf = new byte[(int) len.value() + 1];
        check("lep_session_info", lib.lep_session_info(s, which, buf, new SizeT(buf.length), len), null);
        return text(buf);
    }

    /** Reads samples into Java arrays reused from call to call. */
    static final class Reader {
        final Pointer s;
        final double[] tMono;
        final double[] si; // [n*6]: Fx Fy Fz Mx My Mz

        Reader(Pointer s, int capacity) {
            this.s = s;
            tMono = new double[capacity];
            si = new double[capacity * 6];
        }

        /** One call: how many samples are in tMono and si. */
        int read() throws LepException {
            SizeTByReference n = new SizeTByReference();
            int rc = lib.lep_session_read(s, 1000, new SizeT(tMono.length), n, tMono, null, si,
                    null, null, null, null, null);
            check("lep_session_read", rc, null);
            return (int) n.value();
        }
    }

    static void run() throws LepException {
        System.out.println("leptrino " + lib.lep_version() + " from Java (JNA)");
        byte[] err = new byte[256];
        SizeT errlen = new SizeT(err.length);

        Pointer o = lib.lep_options_new();
        if (o == null) {
            throw new LepException("lep_options_new: out of memory");
        }
        Pointer s;
        try {
            check("option sim", lib.lep_options_set_int(o, "sim", 1, err, errlen), err);
            // a constant load, no noise: the tare visibly zeroes it
            check("option sim-constant", lib.lep_options_set_int(o, "sim-constant", 1, err, errlen), err);
            PointerByReference out = new PointerByReference();
            check("lep_session_open", lib.lep_session_open(o, out, err, errlen), err);
            s = out.getValue();
        } finally {
            lib.lep_options_free(o); // the session copied what it needs
        }
        try {
            session(s);
        } finally {
            lib.lep_session_close(s);
        }
        missingPort(err, errlen);
    }

    static void session(Pointer s) throws LepException {
        // Identity and rated values.
        String model = info(s, LEP_INFO_MODEL);
        System.out.printf("sensor %s serial %s firmware %s%n", model, info(s, LEP_INFO_SERIAL),
                info(s, LEP_INFO_FIRMWARE));
        double[] rated = new double[6];
        check("lep_session_rated", lib.lep_session_rated(s, rated), null);
        System.out.printf("rated Fx %s Fy %s Fz %s N, Mx %s My %s Mz %s N m%n", g(rated[0]),
                g(rated[1]), g(rated[2]), g(rated[3]), g(rated[4]), g(rated[5]));
        if (model.isEmpty() || rated[FZ] <= 0) {
            throw new LepException("no identity or rated values");
        }

        // One second of samples.
        check("lep_session_start", lib.lep_session_start(s), null);
        Reader r = new Reader(s, 256);
        int count = 0;
        double t0 = Double.NaN, tLast = 0, sumFz = 0;
        for (boolean done = false; !done; ) {
            int n = r.read();
            for (int i = 0; i < n; i++) {
                if (Double.isNaN(t0)) {
                    t0 = r.tMono[i];
                }
                if (r.tMono[i] - t0 >= 1.0) {
                    done = true;
                    break;
                }
                count++;
                tLast = r.tMono[i];
                sumFz += r.si[i * 6 + FZ];
            }
        }
        double rate = (count - 1) / (tLast - t0);
        double[] health = new double[lib.lep_session_health_fields().intValue()];
        check("lep_session_health", lib.lep_session_health(s, health, new SizeT(health.length)), null);
        double nominal = health[LEP_H_NOMINAL_HZ];
        System.out.printf("1 s: %d samples, %.1f Hz measured (library: %.1f Hz, nominal %.0f Hz)%n",
                count, rate, health[LEP_H_MEASURED_HZ], nominal);
        if (count < 100 || rate < 0.5 * nominal || rate > 1.5 * nominal) {
            throw new LepException("the rate is off");
        }
        double before = sumFz / count;

        // Tare: average 100 samples, then wait for the LEP_EV_TARE event.
        check("lep_session_tare", lib.lep_session_tare(s, 100, 0), null);
        double[] fields = new double[lib.lep_session_event_fields().intValue()];
        SizeT nfields = new SizeT(fields.length);
        boolean tared = false;
        for (int tries = 0; !tared && tries < 100; tries++) {
            r.read();
            while (!tared && lib.lep_session_next_event(s, fields, nfields) == 1) {
                tared = fields[LEP_EVF_TYPE] == LEP_EV_TARE;
            }
        }
        if (!tared) {
            throw new LepException("no tare event");
        }
        int n = 0;
        double sum = 0;
        while (n < 240) {
            int got = r.read();
            for (int i = 0; i < got; i++) {
                sum += r.si[i * 6 + FZ];
            }
            n += got;
        }
        double after = sum / n;
        System.out.printf("mean Fz %.3f N before the tare, %.3f N after (%d samples)%n", before,
                after, n);
        if (Math.abs(before) < 0.01 * rated[FZ] || Math.abs(after) > 0.005 * rated[FZ]) {
            throw new LepException("the tare did not zero Fz");
        }
        check("lep_session_stop", lib.lep_session_stop(s), null);
    }

    /** A port that does not exist: the library's message and lep_strerror. */
    static void missingPort(byte[] err, SizeT errlen) throws LepException {
        Pointer bad = lib.lep_options_new();
        try {
            check("option port", lib.lep_options_set(bad, "port", "/dev/does-not-exist", err, errlen), err);
            PointerByReference out = new PointerByReference();
            int rc = lib.lep_session_open(bad, out, err, errlen);
            if (rc == LEP_OK || out.getValue() != null) {
                lib.lep_session_close(out.getValue());
                throw new LepException("opening /dev/does-not-exist succeeded");
            }
            System.out.printf("missing port: %s (%d: %s)%n", text(err), rc, lib.lep_strerror(rc));
        } finally {
            lib.lep_options_free(bad);
        }
    }

    static String g(double v) {
        return v == Math.rint(v) ? String.format("%.0f", v) : String.valueOf(v);
    }

    public static void main(String[] args) {
        String path = System.getenv("LEPTRINO_LIB");
        if (path == null || path.isEmpty()) {
            path = "leptrino"; // libleptrino.so on jna.library.path or the loader's path
        }
        try {
            // Strings to and from C as UTF-8 whatever the JVM's default charset.
            lib = Native.load(path, Leptrino.class, Map.of(Library.OPTION_STRING_ENCODING, "UTF-8"));
        } catch (UnsatisfiedLinkError e) {
            System.err.println("leptrino-ffi-java: cannot load " + path + " (set LEPTRINO_LIB): "
                    + e.getMessage());
            System.exit(1);
        }
        try {
            run();
        } catch (LepException e) {
            System.err.println("leptrino-ffi-java: " + e.getMessage());
            System.exit(1);
        }
        System.out.println("ok");
    }
}
