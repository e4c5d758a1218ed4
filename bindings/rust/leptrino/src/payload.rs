//! Payload (leptrino/payload.h): the gravity wrench of a tool on the sensor,
//! and its identification from a few static poses. Pure functions of the
//! library; a session compensates a payload with
//! [`Control::set_payload`](crate::Control::set_payload).

use std::ffi::c_char;

use leptrino_sys as sys;

use crate::error::{check, check_msg, Error, Result};
use crate::options::cstring;
use crate::values::{six, three, Payload};

/// Fields of `lep_payload_identify`.
const FIT_COUNT: usize = sys::LEP_FIT_COUNT as usize;

/// Standard gravity, m/s² (the default gravity vector is (0, 0, -this)).
pub fn standard_gravity() -> f64 {
    // SAFETY: no arguments, no state.
    unsafe { sys::lep_standard_gravity() }
}

impl Payload {
    /// Its gravity wrench at `gravity` (sensor frame, m/s²): (m g, c × m g),
    /// N and N·m. `ErrorKind::Arg` for non-finite values or a negative mass.
    ///
    /// ```
    /// let p = leptrino::Payload::new(1.0, [0.0, 0.0, 0.1]);
    /// let w = p.wrench([9.81, 0.0, 0.0])?;
    /// assert_eq!(w[0], 9.81);
    /// assert!((w[4] - 0.981).abs() < 1e-12);
    /// # Ok::<(), leptrino::Error>(())
    /// ```
    pub fn wrench(&self, gravity: [f64; 3]) -> Result<[f64; 6]> {
        let p = self.to_array();
        let mut w = [0.0; 6];
        // SAFETY: 4, 3 and 6 doubles.
        let rc = unsafe { sys::lep_payload_wrench(p.as_ptr(), gravity.as_ptr(), w.as_mut_ptr()) };
        check(rc, &format!("payload {self:?} at gravity {gravity:?}"))?;
        Ok(w)
    }
}

/// What [`identify_payload`] found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PayloadFit {
    /// Mass and centre of mass.
    pub payload: Payload,
    /// The sensor's force bias, N.
    pub force_bias_n: [f64; 3],
    /// The sensor's torque bias, N·m.
    pub torque_bias_nm: [f64; 3],
    /// Per axis, RMS over the poses of measured - model (N, N·m).
    pub residual: [f64; 6],
    /// How well the gravity vectors cover the directions (0 on one line,
    /// up to 1 for poses spread evenly over the sphere).
    pub spread: f64,
    /// Poses used.
    pub poses: usize,
}

/// Identify a payload and the sensor's biases from static poses: at pose i
/// gravity\[i\] (m/s², sensor frame) and wrench\[i\] (the mean measured there,
/// N and N·m, not tared). `ErrorKind::Value` when the poses do not determine
/// the payload (fewer than 3, too little spread, a mass not positive),
/// `ErrorKind::Arg` for non-finite values or slices of different lengths;
/// the library's message says which.
pub fn identify_payload(gravity: &[[f64; 3]], wrench: &[[f64; 6]]) -> Result<PayloadFit> {
    if gravity.len() != wrench.len() {
        return Err(Error::arg(format!(
            "identify_payload: {} gravity vectors for {} wrenches",
            gravity.len(),
            wrench.len()
        )));
    }
    let g: Vec<f64> = gravity.iter().flatten().copied().collect();
    let w: Vec<f64> = wrench.iter().flatten().copied().collect();
    let mut fit = [0.0; FIT_COUNT];
    let mut err = [0u8; 256];
    // SAFETY: n*3 and n*6 doubles, FIT_COUNT out, err of its size.
    let rc = unsafe {
        sys::lep_payload_identify(
            g.as_ptr(),
            w.as_ptr(),
            gravity.len(),
            fit.as_mut_ptr(),
            FIT_COUNT,
            err.as_mut_ptr().cast::<c_char>(),
            err.len(),
        )
    };
    check_msg(rc, &err, "identify_payload")?;
    let p = sys::LEP_FIT_PAYLOAD as usize;
    Ok(PayloadFit {
        payload: Payload::new(fit[p], [fit[p + 1], fit[p + 2], fit[p + 3]]),
        force_bias_n: three(&fit, sys::LEP_FIT_FORCE_BIAS_N),
        torque_bias_nm: three(&fit, sys::LEP_FIT_TORQUE_BIAS_NM),
        residual: six(&fit, sys::LEP_FIT_RESIDUAL),
        spread: fit[sys::LEP_FIT_SPREAD as usize],
        poses: fit[sys::LEP_FIT_POSES as usize] as usize,
    })
}

/// The mean wrench of one pose from a CSV recording of `leptrino stream`
/// (sensor frame, N and N·m, any tare added back) and the rows averaged.
pub fn pose_mean(path: &str) -> Result<([f64; 6], u64)> {
    let p = cstring("path", path)?;
    let mut mean = [0.0; 6];
    let mut n = 0u64;
    let mut err = [0u8; 512];
    // SAFETY: a NUL-terminated path, 6 doubles, out pointer, err of its size.
    let rc = unsafe {
        sys::lep_payload_pose_read(
            p.as_ptr(),
            mean.as_mut_ptr(),
            &mut n,
            err.as_mut_ptr().cast::<c_char>(),
            err.len(),
        )
    };
    check_msg(rc, &err, path)?;
    Ok((mean, n))
}
