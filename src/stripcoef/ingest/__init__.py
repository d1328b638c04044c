"""Real logs in: a column map (YAML) reads any CSV, several streams merged by time, and ROS 1/2
bags (optional extra ``stripcoef[ros]``) into the log format of :mod:`stripcoef.logfile`.

- :mod:`.mapfile`: the map's schema, validated into :class:`LogMap` (docs/logs.md);
- :mod:`.streams`: CSV streams (with or without header, one file or chunk files), their times
  and sampling checks;
- :mod:`.clock`: a stream's clock offset to another (cross-correlation of a shared signal) and
  a fixed-rate source re-timed from its bursty receive times;
- :mod:`.bags`: topics of a ROS bag as streams (``rosbags``, no ROS install);
- :mod:`.attitude`: Euler angles, quaternions, NED/ENU and FRD/FLU, body rates from attitude;
- :mod:`.merge`: the streams on one time grid (linear for states, zero-order hold for inputs).

Depends on: logfile, conventions, files, errors (the layer right above ``logfile``).
"""

from stripcoef.ingest.mapfile import LogMap, load_map, parse_map
from stripcoef.ingest.merge import build_log, read_any_log, read_mapped_log

__all__ = ["LogMap", "load_map", "parse_map", "build_log", "read_any_log", "read_mapped_log"]
