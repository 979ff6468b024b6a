//! Table names as `&'static str` for [`varmass_core::SystemError::TableOutside`], which
//! generated code fills from string literals: the interpreter knows its tables' names only
//! at run time, so each distinct name is leaked once, process-wide, and shared after.

use std::collections::BTreeSet;
use std::sync::{Mutex, OnceLock};

/// The `'static` copy of `name`, leaked on its first use only.
pub(crate) fn intern(name: &str) -> &'static str {
    static NAMES: OnceLock<Mutex<BTreeSet<&'static str>>> = OnceLock::new();
    let names = NAMES.get_or_init(|| Mutex::new(BTreeSet::new()));
    // A poisoned lock still holds a valid set: nothing can panic while it is held.
    let mut names = names
        .lock()
        .unwrap_or_else(|poisoned| poisoned.into_inner());
    if let Some(known) = names.get(name) {
        return known;
    }
    let leaked: &'static str = Box::leak(name.to_owned().into_boxed_str());
    names.insert(leaked);
    leaked
}

/// The `'static` copy of a list of names (each [`intern`]ed), leaked on its first use only:
/// a run-time model's parameter names for
/// [`VariableMassSystem::parameter_names`](varmass_core::VariableMassSystem::parameter_names).
pub(crate) fn intern_list(list: &[&str]) -> &'static [&'static str] {
    static LISTS: OnceLock<Mutex<BTreeSet<&'static [&'static str]>>> = OnceLock::new();
    let lists = LISTS.get_or_init(|| Mutex::new(BTreeSet::new()));
    let interned: Vec<&'static str> = list.iter().map(|name| intern(name)).collect();
    let mut lists = lists
        .lock()
        .unwrap_or_else(|poisoned| poisoned.into_inner());
    if let Some(known) = lists.get(interned.as_slice()) {
        return known;
    }
    let leaked: &'static [&'static str] = Box::leak(interned.into_boxed_slice());
    lists.insert(leaked);
    leaked
}
