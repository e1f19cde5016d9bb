#!/bin/bash
# The drum of Alizadeh et al. (2013) against its measured velocity profile
# (README.md): for each bead friction, speed, stiffness and seed,
# alizadeh.toml turned 1.5 revolutions (the start-up), then its fields in
# the drum's frame over the next second (50 states 0.02 s apart; the states
# are taken twice, so 2 s more of the drum), along the middle fifth of the
# surface, a Gaussian kernel of one bead radius on a 1 mm grid. A finished
# run is skipped, so the script resumes where it stopped; analyse.py --keep
# then keeps what the tables and figures need (kept/, about 20 kB a run).
#     bash studies/drum_flow/run.sh [TUMBLE] [OUT]   (default build/tumble, studies/drum_flow/out)
# The runs (environment; the defaults in brackets):
#     FRICTIONS ["0.3"]   bead friction: 0.3 is the Lethe project's model of this
#                         drum; "0.3 0.5" adds 0.5, which follows Jop et al.'s
#                         mu(I) in studies/mu_i
#     SPEEDS ["11.6"]     the drum's speed, rpm: 11.6 is the measured drum's;
#                         "5.8 11.6 17.4" the layer against the speed
#                         (runs named mu0.3_rpm5.8_seed1, ...)
#     STIFFNESS ["1"]     the beads' E and G times this, their viscosities
#                         times its 3/5 power, so that the restitution stays
#                         (tumble contact: 0.9745 and 0.960 at 0.1 and 1 m/s
#                         for 1 and 10); "10": glass softened a thousandfold,
#                         not ten thousandfold (runs named mu0.3_E10x_seed1)
#     SEEDS ["1 2 3"]
# Cost on one core (AMD Zen 5), alone: about 13 minutes a run at 11.6 rpm,
# 23 at 5.8 and 10 at 17.4 (the revolutions take longer at a lower speed),
# 2.5 times as long with STIFFNESS=10 (the step is 2.5 times shorter).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
tumble=${1:-$here/../../build/tumble}
out=${2:-$here/out}
mkdir -p "$out"
for mu in ${FRICTIONS:-0.3}; do
    for rpm in ${SPEEDS:-11.6}; do
        for stiff in ${STIFFNESS:-1}; do
            name=mu$mu
            [ "$rpm" = 11.6 ] || name=${name}_rpm$rpm
            [ "$stiff" = 1 ] || name=${name}_E${stiff}x
            edits=(-e "s/^mu = 0.3 .*/mu = $mu/")
            if [ "$rpm" != 11.6 ]; then
                edits+=(-e "s/^omega = 1.2147 .*/omega = $(awk -v r="$rpm" 'BEGIN {printf "%.6g", r * 3.14159265358979 / 30}')/")
            fi
            if [ "$stiff" != 1 ]; then
                read -r E G xi < <(awk -v k="$stiff" 'BEGIN {printf "%.6e %.6e %.6e\n", 6.3e6 * k, 2.6e6 * k, 8.0 * k ^ 0.6}')
                edits+=(-e "s/^E = 6.3e6/E = $E/" -e "s/^G = 2.6e6/G = $G/" -e "s/^xi = 8.0/xi = $xi/" -e "s/^eta = 8.0/eta = $xi/")
            fi
            sed "${edits[@]}" "$here/alizadeh.toml" > "$out/alizadeh_$name.toml"
            for seed in ${SEEDS:-1 2 3}; do
                run="$out/${name}_seed$seed"
                [ -f "$run/flowing_layer/drum_frame.json" ] && continue
                [ -f "$run/summary.json" ] || "$tumble" drum -q --no-plot --config "$out/alizadeh_$name.toml" \
                    --seed "$seed" --threads 1 -o "$run" --force
                "$tumble" fields "$run" --frame drum --samples 50 --every 0.02 --kernel gaussian \
                    --width 0.0015 --cell 0.001 --span 0.2 -q
            done
        done
    done
done
python3 "$here/analyse.py" --keep "$out"
