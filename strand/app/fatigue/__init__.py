"""A run's fatigue outputs: the histories it records (``recorders``), the report read from them
(``report``: per pair ``crossings``, per element and wire ``wire_stresses``, the strand-level T–N
check ``tension_check``; what it found ``findings``, its text ``text``, its figures ``figures``,
its CSV files ``csv_table``), a spectrum's damage over a sweep (``spectrum``, with
``spectrum_findings`` and ``spectrum_text``) and a load history reduced to a spectrum
(``load_history``). The physics they use is the library's ``strand.fatigue``."""
