#!/bin/sh
# check_one_step.sh NM OBJECTS... - the chain sensors -> estimator -> modes /
# holds -> guard -> law -> output stage is called from fw_step.o only: any
# other object (a host: the SIL board, the HIL firmware, a main loop) that
# references one of these functions keeps a copy of the step. Exits 1 and
# names the object and the symbol. Run on the host objects (firmware/
# CMakeLists.txt) and on the Matek F405-WING image's board objects, built for
# the target (boards/matekf405wing/CMakeLists.txt: matek_one_step_*).
nm="$1"
shift
chain='ht_step ht_dcm_update ht_modes_step ht_alt_hold_step_v ht_speed_hold_step ht_upset_guard_step os_compute'
also='ht_modes_fly' # the modes' own shortcut of the chain: no host may call it either
status=0
seen_step=0
for obj in "$@"; do
    for o in $(echo "$obj" | tr ';' ' '); do
        undef=$("$nm" -u "$o" 2>/dev/null | awk '{print $NF}')
        case "$o" in
        *fw_step.c.o*)
            for f in $chain; do
                echo "$undef" | grep -qx "$f" || { echo "fw_step.o does not call $f"; status=1; }
            done
            seen_step=1
            continue ;;
        esac
        for f in $chain $also; do
            if echo "$undef" | grep -qx "$f"; then
                echo "$o calls $f: a host keeps its own copy of the firmware step"
                status=1
            fi
        done
    done
done
[ "$seen_step" = 1 ] || { echo "fw_step.o not among the objects"; status=1; }
exit $status
