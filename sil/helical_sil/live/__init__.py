"""Flights that talk to something outside the process, step by step.

Owns: serve.py (`serve`: the scenario's aircraft flown live for a ground
station over MAVLink UDP, the firmware's link building and parsing every
message) and pil.py (processor-in-the-loop: the STM32F405 HIL firmware
image under QEMU computes each control step, `run --target pil`).

May import: sim, config and sensors; not campaigns, not cli.
Imported by: cli.
"""
