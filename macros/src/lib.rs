//! The `#[variable_mass_system("…")]` attribute macro of varmass. A thin entry point: the
//! work (parse → derive → emit) lives in `varmass-symbolic` so that it can be unit-tested.
//! The macro itself arrives with the code-generation stage; until then this crate is empty.
