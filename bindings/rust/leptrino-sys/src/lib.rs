//! Raw declarations of libleptrino, generated at build time by bindgen from
//! `include/leptrino/*.h` (every public header: frame and message codecs,
//! client, device, serial port, virtual sensor, session, output writer).
//!
//! The contracts (ownership, blocking, timeouts, errors, threads) are the
//! headers' comments, carried over as doc comments. Use the `leptrino` crate
//! for a safe API over the session.
//!
//! The library is an installed libleptrino found by pkg-config, or else the C
//! sources this crate carries, compiled by its build script (see build.rs).
//!
//! ```
//! let v = unsafe { std::ffi::CStr::from_ptr(leptrino_sys::lep_version()) };
//! assert_eq!(v.to_str().unwrap(), env!("CARGO_PKG_VERSION"));
//! ```
#![no_std]
#![allow(non_upper_case_globals, non_camel_case_types, non_snake_case)]
#![allow(clippy::all)]
#![allow(
    rustdoc::broken_intra_doc_links,
    rustdoc::invalid_html_tags,
    rustdoc::bare_urls
)]

include!(concat!(env!("OUT_DIR"), "/bindings.rs"));

include!(concat!(env!("OUT_DIR"), "/error_kind.rs"));

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn error_kinds_follow_the_header() {
        assert!(ErrorKind::from_code(LEP_OK).is_none());
        for &k in ErrorKind::ALL {
            assert_eq!(ErrorKind::from_code(k.code()), Some(k));
            assert!(k.code() < 0 && k.c_name().starts_with("LEP_E_"));
        }
        assert_eq!(
            ErrorKind::from_code(LEP_E_TIMEOUT),
            Some(ErrorKind::Timeout)
        );
        assert_eq!(ErrorKind::TooLong.c_name(), "LEP_E_TOO_LONG");
    }

    #[test]
    fn header_version_is_the_crate_version() {
        let v: &[u8] = LEP_VERSION_STRING;
        assert_eq!(&v[..v.len() - 1], env!("CARGO_PKG_VERSION").as_bytes());
    }
}
