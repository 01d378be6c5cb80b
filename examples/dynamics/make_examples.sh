#!/bin/sh
# The example files of this folder, made on the virtual machine (run from the repository's root).
set -e
cd examples/dynamics
M=../xz_module/machine.toml
# the step cycle over two 5 mm pitches of a screw with a 0.4 um periodic error, 3 runs, captured stop and go
# (the recording, 200 s at 50 Hz, is not kept)
axiscal plan --step-cycle --start-mm 100 --period-mm 5 --periods 2 --runs 3 -o step_cycle.csv \
    --gcode step_cycle.ngc --dwell-s 0.8 --feed-mm-min 600
axiscal simulate capture step_cycle.ngc --machine $M --axis X --rate-hz 50 --periodic-um 0.4 --pitch-mm 5 \
    -o step_cycle_recording.csv
axiscal capture step_cycle.csv --from step_cycle_recording.csv -o step_cycle_run.csv
rm step_cycle_recording.csv step_cycle_recording.json
# an on-the-fly run at 1000 mm/min, the controller's position stream 8 ms late
axiscal plan --start-mm 0 --end-mm 100 --targets 5 --runs 1 --seed 3 -o fly_plan.csv --gcode fly.ngc --on-the-fly \
    --feed-mm-min 1000
axiscal simulate capture fly.ngc --machine $M --axis X --continuous --position-delay-ms 8 --rate-hz 250 \
    -o fly_recording.csv
