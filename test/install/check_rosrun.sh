#!/usr/bin/env bash
# What `rosrun rigid_body_sim PROGRAM` runs with only SPACE/setup.bash sourced (a devel or an install space):
# the program in SPACE/lib/rigid_body_sim, for every program the package installs, never a copy elsewhere in
# the package's folder (another build under build/, the sources in scripts/). rosrun --prefix echo prints
# the path it would run; with stdin closed, a choice between two (rosrun's prompt) prints none.
# A decoy `simulate` under <package>/build/ (where the Makefile keeps its other builds) must not be taken.
# Usage: check_rosrun.sh SPACE
set -euo pipefail
space=$(cd "$1" && pwd)
env -i HOME="$HOME" PATH=/usr/bin:/bin bash -c '
  set -euo pipefail
  space=$1
  set +u; source "$space/setup.bash"; set -u
  package=$(rospack find rigid_body_sim)
  decoy=
  if [[ -w $package && -d $package/build ]]; then
    decoy=$(mktemp -d "$package/build/rosrun-decoy.XXXXXX")
    trap "rm -rf \"$decoy\"" EXIT
    printf "#!/bin/sh\necho decoy\n" >"$decoy/simulate" && chmod +x "$decoy/simulate"
  fi
  failed=0
  for program in sim_node simulate simulate_ros plot_run.py bag_summary.py slurm_sweep; do
    runs=$(rosrun --prefix echo rigid_body_sim "$program" </dev/null 2>/dev/null || true)
    if [[ $runs != "$space/lib/rigid_body_sim/$program" ]]; then
      echo "check_rosrun: rosrun rigid_body_sim $program runs \"$runs\", not $space/lib/rigid_body_sim/$program" >&2
      failed=1
    fi
  done
  ((failed == 0)) || exit 1
  echo "check_rosrun: rosrun runs every program from $space${decoy:+ (a decoy under $package/build/ left alone)}"
' check_rosrun "$space"
