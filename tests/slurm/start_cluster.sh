# Sourced by the SLURM tests after they set $work: a fresh work folder with a one-node
# cluster in it (cluster.sh), stopped when the test exits whichever way.
slurm_here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
rm -rf "$work"
mkdir -p "$work"
export SLURM_CONF="$work/cluster/slurm.conf"
trap 'bash "$slurm_here/cluster.sh" stop "$work/cluster"' EXIT
bash "$slurm_here/cluster.sh" start "$work/cluster"
