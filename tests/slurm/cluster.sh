#!/usr/bin/env bash
# A Slurm cluster of four nodes on this machine, from Debian's packages, for the tests: every
# file under one folder, loopback and free ports only, no accounting.
#   source cluster.sh; cluster_start DIR; ...; cluster_stop DIR
# cluster_start exports SLURM_CONF; cluster_stop ends every daemon (TERM, then KILL) and is safe
# to call twice, from a trap. Needs root, and slurmctld slurmd slurm-client munge installed.

cluster_free_ports() {  # COUNT: the first of COUNT consecutive free loopback ports
  python3 - "$1" <<'PY'
import random, socket, sys
count = int(sys.argv[1])
for _ in range(200):
    base = random.randrange(20000, 60000 - count)
    sockets = []
    try:
        for port in range(base, base + count):
            s = socket.socket()
            s.bind(("127.0.0.1", port))
            sockets.append(s)
        print(base)
        break
    except OSError:
        pass
    finally:
        for s in sockets:
            s.close()
else:
    sys.exit("no free ports")
PY
}

cluster_start() {
  local dir=$1 base
  mkdir -p "$dir/state" "$dir/spool" "$dir/munge"
  chmod 755 "$dir"
  chown munge:munge "$dir/munge"
  chmod 711 "$dir/munge"  # munged wants its socket reachable by all, its folder not writable
  base=$(cluster_free_ports 5) || return 1
  cat > "$dir/slurm.conf" <<CONF
ClusterName=glinttest
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort=$base
SlurmUser=root
AuthType=auth/munge
AuthInfo=socket=$dir/munge/munge.socket,cred_expire=10
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool/%n
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd-%n.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd-%n.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/backfill
SchedulerParameters=bf_interval=1,sched_interval=1,kill_invalid_depend
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
ReturnToService=2
SlurmdTimeout=5
SlurmctldTimeout=10
MessageTimeout=5
MinJobAge=300
NodeName=node[1-4] NodeHostname=localhost NodeAddr=127.0.0.1 Port=[$((base + 1))-$((base + 4))] CPUs=1 RealMemory=1000 State=UNKNOWN
PartitionName=debug Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
  export SLURM_CONF=$dir/slurm.conf
  runuser -u munge -- /usr/sbin/munged --socket="$dir/munge/munge.socket" --pid-file="$dir/munge/munged.pid" \
    --log-file="$dir/munge/munged.log" --seed-file="$dir/munge/munged.seed" || return 1
  slurmctld -f "$SLURM_CONF" -i || return 1
  local node
  for node in node1 node2 node3 node4; do slurmd -f "$SLURM_CONF" -N "$node" || return 1; done
  local tries
  for tries in $(seq 60); do
    [ "$(sinfo -h -t idle -o %D 2> /dev/null)" = 4 ] && return 0
    sleep 0.5
  done
  echo "cluster: the four nodes did not come up:" >&2
  sinfo >&2
  return 1
}

cluster_processes() {  # DIR: every process started with this cluster's SLURM_CONF (the daemons, their steps and tasks)
  grep -lz "^SLURM_CONF=$1/slurm.conf$" /proc/[0-9]*/environ 2> /dev/null | cut -d/ -f3 || true
}

cluster_pids() {  # DIR: the daemons' pids, and the job steps and their tasks
  local dir=$1 file
  for file in "$dir"/slurmd-*.pid "$dir/slurmctld.pid" "$dir/munge/munged.pid"; do
    [ -s "$file" ] && cat "$file"
  done
  cluster_processes "$dir"
}

cluster_stop() {
  local dir=$1 pids
  [ -d "$dir" ] || return 0
  pids=$(cluster_pids "$dir" | sort -u | grep -vx "$$" || true)
  [ -n "$pids" ] && kill $pids 2> /dev/null
  for _ in $(seq 20); do
    pids=$(for p in $pids; do [ -d "/proc/$p" ] && echo "$p"; done)
    [ -z "$pids" ] && break
    sleep 0.25
  done
  [ -n "$pids" ] && kill -9 $pids 2> /dev/null
  return 0
}

cluster_kill_node() {  # DIR NODE: the node's slurmd, its job steps and their tasks, with SIGKILL
  local dir=$1 node=$2 pids tasks p
  tasks=$(for p in $(cluster_processes "$dir"); do
    grep -qz "^SLURMD_NODENAME=$node$" "/proc/$p/environ" 2> /dev/null && echo "$p"
  done)
  pids="$(cat "$dir/slurmd-$node.pid") $tasks"
  for p in $tasks; do  # the node's steps: the parents of its tasks (ppid: the field after the state)
    pids="$pids $(sed 's/.*) [A-Za-z] \([0-9]*\).*/\1/' "/proc/$p/stat" 2> /dev/null)"
  done
  kill -9 $pids 2> /dev/null || true
}
