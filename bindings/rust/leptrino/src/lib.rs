pub use leptrino_sys as sys;
