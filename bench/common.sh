# SPDX-License-Identifier: MIT
# shellcheck shell=bash
# Shell helpers of the bench/ scripts, sourced by each (not run alone).
# The calling script is "$0".

# The script's header comment, the lines after the licence, as its help.
usage() { awk 'NR > 2 && !/^#/ { exit } NR > 2 { sub(/^# ?/, ""); print }' "$0"; }
# The message on standard error, named by the script, and exit 1.
die() { echo "$(basename "$0"): $*" >&2; exit 1; }
# need_int OPTION VALUE: VALUE must be a positive integer.
need_int() { [[ "$2" =~ ^[1-9][0-9]*$ ]] || die "$1 needs a positive integer, got '$2'"; }
