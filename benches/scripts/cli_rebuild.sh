#!/usr/bin/env bash
# The README's rebuild time of the command line tool: CPU seconds (user + system) to
# rebuild the `cli` crate (its library and the `varmass` binary) in release after a change
# to its library, its dependencies already built (the dispatch table in
# cli/src/run/dispatch.rs, in the library, monomorphizes every stepper for every supported
# size, which is most of it; touching only main.rs would rebuild the thin binary alone).
# The load average is printed beside the figure: CPU seconds grow on a busy machine too.
#
#   bash benches/scripts/cli_rebuild.sh
set -euo pipefail
cd "$(dirname "$0")/../.."
cargo build --quiet --release -p varmass-cli
touch cli/src/lib.rs
uptime
/usr/bin/time -f "cli crate, release rebuild: %U s user + %S s system, %e s wall" \
    cargo build --quiet --release -p varmass-cli
