#!/usr/bin/env bash
# The README's rebuild time of the command line tool: CPU seconds (user + system) to
# rebuild the `cli` crate alone in release after a change to it, its dependencies already
# built (the dispatch table in cli/src/run/dispatch.rs monomorphizes every stepper for
# every supported size, which is most of it).
#
#   bash benches/scripts/cli_rebuild.sh
set -euo pipefail
cd "$(dirname "$0")/../.."
cargo build --quiet --release -p varmass-cli
touch cli/src/main.rs
/usr/bin/time -f "cli crate, release rebuild: %U s user + %S s system, %e s wall" \
    cargo build --quiet --release -p varmass-cli
