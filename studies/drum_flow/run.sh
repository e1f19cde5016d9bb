#!/bin/bash
# The drum of Alizadeh et al. (2013) against its measured velocity profile
# (README.md): for each bead friction, speed and seed, alizadeh.toml turned
# 1.5 revolutions (the start-up), then its fields in the drum's frame over
# the next second (50 states 0.02 s apart; the states are taken twice, so
# 2 s more of the drum), along the middle fifth of the surface, a Gaussian
# kernel of one bead radius on a 1 mm grid. A finished run is skipped, so
# the script resumes where it stopped; analyse.py --keep then keeps what the
# table and figure need (kept/, about 20 kB a run).
#     bash studies/drum_flow/run.sh [TUMBLE] [OUT]   (default build/tumble, studies/drum_flow/out)
#     FRICTIONS="0.3", SPEEDS="11.6" and SEEDS="1 2 3" (the defaults) choose the
#     runs: the bead friction of the Lethe project's model of this drum, the
#     measured drum's speed in rpm. FRICTIONS="0.3 0.5" adds 0.5, which
#     follows Jop et al.'s mu(I) in studies/mu_i; SPEEDS="5.8 11.6 17.4" the
#     layer against the drum's speed (runs named mu0.3_rpm5.8_seed1, ...).
# Cost on one core (AMD Zen 5), alone: about 13 minutes a run at 11.6 rpm,
# 23 at 5.8 and 10 at 17.4 (the revolutions take longer at a lower speed).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
tumble=${1:-$here/../../build/tumble}
out=${2:-$here/out}
mkdir -p "$out"
for mu in ${FRICTIONS:-0.3}; do
    for rpm in ${SPEEDS:-11.6}; do
        name=mu$mu
        [ "$rpm" = 11.6 ] || name=mu${mu}_rpm$rpm
        omega=$(awk -v r="$rpm" 'BEGIN {printf "%.6g", r * 2 * 3.14159265358979 / 60}')
        sed -e "s/^mu = 0.3 .*/mu = $mu/" -e "s/^omega = 1.2147 .*/omega = $omega/" \
            "$here/alizadeh.toml" > "$out/alizadeh_$name.toml"
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
python3 "$here/analyse.py" --keep "$out"
