#!/usr/bin/env bash
# Prints how many cores this machine really lets us use: nproc, lowered to the cgroup's CPU quota
# when there is one (a container limited to 2 CPUs on a 64-core host reports 64 to nproc, and
# `make -j64` / `ctest -j64` on 2 cores makes every timed test crawl).
n=$(nproc)
if [[ -r /sys/fs/cgroup/cpu.max ]]; then
  read -r quota period < /sys/fs/cgroup/cpu.max
  if [[ "$quota" != max && "$period" -gt 0 ]]; then
    q=$(( (quota + period - 1) / period ))
    (( q >= 1 && q < n )) && n=$q
  fi
elif [[ -r /sys/fs/cgroup/cpu/cpu.cfs_quota_us && -r /sys/fs/cgroup/cpu/cpu.cfs_period_us ]]; then
  quota=$(cat /sys/fs/cgroup/cpu/cpu.cfs_quota_us); period=$(cat /sys/fs/cgroup/cpu/cpu.cfs_period_us)
  if [[ "$quota" -gt 0 && "$period" -gt 0 ]]; then
    q=$(( (quota + period - 1) / period ))
    (( q >= 1 && q < n )) && n=$q
  fi
fi
echo "$n"
