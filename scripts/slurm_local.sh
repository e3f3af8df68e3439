#!/bin/sh
# A single-node Slurm cluster on this machine, for testing the slurm executor of `vdec sweep`
# and of the verification harness (tests/python/test_slurm_executor.py).
#
#   scripts/slurm_local.sh start     install slurm-wlm and munge (apt-get, once), write
#                                    /etc/slurm/slurm.conf for this machine, start munged,
#                                    slurmctld and slurmd, and wait until `sinfo` answers
#   scripts/slurm_local.sh stop      stop the three daemons this script started (by their pid files)
#   scripts/slurm_local.sh status    sinfo, or say that no cluster answers
#
# Run as root (it installs packages and writes /etc/slurm). Slurm runs as root here, without
# accounting (sacct has no records: the executor asks scontrol instead), one partition "local"
# holding this machine with all its CPUs, one CPU per task by default. Logs: /var/log/slurm/.
set -eu

CONF_DIR=/etc/slurm
STATE_DIR=/var/lib/slurm-local
LOG_DIR=/var/log/slurm
RUN_DIR=/run/slurm-local
MUNGE_PID=/run/munge/munged.pid

die() { echo "slurm_local.sh: $*" >&2; exit 1; }

install_packages() {
    if command -v slurmctld >/dev/null && command -v slurmd >/dev/null && command -v munged >/dev/null; then
        return
    fi
    DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends slurm-wlm munge >/dev/null \
        || die "apt-get install slurm-wlm munge failed"
}

write_config() {
    host=$(hostname -s)
    cpus=$(nproc)
    # slurmd drains a node that has less memory than configured: claim 90 % of what there is.
    memory_mb=$(awk '/^MemTotal:/ { printf "%d", $2 / 1024 * 0.9 }' /proc/meminfo)
    mkdir -p "$CONF_DIR" "$STATE_DIR/ctld" "$STATE_DIR/d" "$LOG_DIR" "$RUN_DIR"
    cat >"$CONF_DIR/slurm.conf" <<EOF
# Written by vdec's scripts/slurm_local.sh: a one-node cluster on $host.
ClusterName=vdec-local
SlurmctldHost=$host(127.0.0.1)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
StateSaveLocation=$STATE_DIR/ctld
SlurmdSpoolDir=$STATE_DIR/d
SlurmctldPidFile=$RUN_DIR/slurmctld.pid
SlurmdPidFile=$RUN_DIR/slurmd.pid
SlurmctldLogFile=$LOG_DIR/slurmctld.log
SlurmdLogFile=$LOG_DIR/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
JobCompType=jobcomp/none
MpiDefault=none
ReturnToService=2
# Finished jobs stay visible to scontrol for ten minutes: without accounting, that is where
# the executor reads the state of a task that failed.
MinJobAge=600
# Start a task as soon as a CPU is free, instead of batching the starts (3 s by default):
# a sweep of short runs is all starts.
SchedulerParameters=batch_sched_delay=0
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$memory_mb State=UNKNOWN
PartitionName=local Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
}

running() { [ -f "$1" ] && kill -0 "$(cat "$1")" 2>/dev/null; }

start_munge() {
    running "$MUNGE_PID" && return
    [ -f /etc/munge/munge.key ] || mungekey --create --keyfile=/etc/munge/munge.key
    chown munge:munge /etc/munge/munge.key
    chmod 0400 /etc/munge/munge.key
    mkdir -p /run/munge
    chown munge:munge /run/munge
    runuser -u munge -- /usr/sbin/munged --pid-file="$MUNGE_PID" || die "munged did not start"
}

start() {
    install_packages
    write_config
    start_munge
    running "$RUN_DIR/slurmctld.pid" || slurmctld || die "slurmctld did not start (see $LOG_DIR/slurmctld.log)"
    running "$RUN_DIR/slurmd.pid" || slurmd || die "slurmd did not start (see $LOG_DIR/slurmd.log)"
    for _ in $(seq 1 30); do
        if sinfo -h -o '%T' 2>/dev/null | grep -q -E '^(idle|mixed|allocated)'; then
            sinfo
            return
        fi
        sleep 1
    done
    sinfo >&2 || true
    die "the node did not come up within 30 s (see $LOG_DIR/)"
}

stop_daemon() {
    if running "$1"; then
        kill "$(cat "$1")"
    fi
    rm -f "$1"
}

stop() {
    stop_daemon "$RUN_DIR/slurmd.pid"
    stop_daemon "$RUN_DIR/slurmctld.pid"
    stop_daemon "$MUNGE_PID"
}

case "${1:-}" in
    start) start ;;
    stop) stop ;;
    status) sinfo 2>/dev/null || die "no Slurm cluster answers (scripts/slurm_local.sh start)" ;;
    *) echo "usage: scripts/slurm_local.sh start|stop|status" >&2; exit 2 ;;
esac
