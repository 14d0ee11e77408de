#!/usr/bin/env bash
# make cluster-test: a one-node Slurm of its own (scripts/local_slurm in DIR), then
#  1. the text's random theta0 over 10,000 rods in 8 shards through scripts/slurm_sweep: sweep.csv must be
#     byte for byte the single-machine `simulate --sweep` of the same;
#  2. a sweep whose shard 2 of 3 fails (a stand-in for simulate that exits 3 there): slurm_sweep must exit
#     non-zero and name that shard.
# The cluster goes down and DIR is removed however it ends. Usage: cluster_test.sh DEVEL DIR
set -euo pipefail
export PATH=/usr/bin:$PATH
devel=$(realpath "$1")
set +u; source "$devel/setup.bash"; set -u  # slurm_sweep reads the package's description
dir=$(realpath -m "$2")
simulate=$devel/lib/rigid_body_sim/simulate
sweep=(config/rod.yaml --sweep rod.theta0=0:6.283185307179586:10000 --duration 10)
start=$SECONDS

finish() {
  local status=$?
  if ((status != 0)) && [[ -d $dir/sweeps ]]; then
    echo "cluster-test: FAILED; the end of every log:" >&2
    for log in "$dir"/log/slurmctld.log "$dir"/log/slurmd.log "$dir"/sweeps/*/logs/*.log; do
      [[ -f $log ]] && { echo "--- $log" >&2; tail -5 "$log" >&2; }
    done
  fi
  bash scripts/local_slurm down "$dir" >/dev/null
  echo "cluster-test: $( ((status == 0)) && echo passed || echo FAILED) in $((SECONDS - start)) s"
  exit "$status"
}
trap finish EXIT
trap "exit 130" INT TERM  # through finish as well

bash scripts/local_slurm up "$dir"
export SLURM_CONF=$dir/slurm.conf
mkdir "$dir/sweeps"

echo "== 10,000 rods in 8 shards, against the single-machine sweep"
"$simulate" "${sweep[@]}" --out-dir "$dir/sweeps/single" >/dev/null
python3 scripts/slurm_sweep "${sweep[@]}" --shards 8 --out-dir "$dir/sweeps/slurm" --simulate "$simulate" --timeout 90
cmp "$dir/sweeps/single/sweep.csv" "$dir/sweeps/slurm/sweep.csv"
echo "cluster-test: sweep.csv is byte for byte the single-machine one ($(wc -l <"$dir/sweeps/single/sweep.csv") lines)"

echo "== a failing shard is named"
failing=$dir/sweeps/failing_simulate
cat >"$failing" <<SCRIPT
#!/bin/bash
# simulate, except that shard 2 of 3 fails
[[ " \$* " == *" 2/3 "* ]] && { echo "failing_simulate: shard 2 fails" >&2; exit 3; }
exec "$simulate" "\$@"
SCRIPT
chmod +x "$failing"
if python3 scripts/slurm_sweep config/rod.yaml --sweep rod.theta0=0:1:30 --shards 3 --out-dir "$dir/sweeps/failing" \
     --simulate "$failing" --timeout 60 2>"$dir/sweeps/failing.err"; then
  echo "cluster-test: slurm_sweep exited 0 although shard 2 failed" >&2
  exit 1
fi
cat "$dir/sweeps/failing.err"
grep -q "shard 2/3 (job [0-9]*_2) failed: exit status 3" "$dir/sweeps/failing.err"
if grep "shard [13]/3" "$dir/sweeps/failing.err"; then
  echo "cluster-test: a shard that succeeded was named" >&2
  exit 1
fi
