"""A run's fatigue outputs: the histories it records (``recorders``), the report read from them
(``report``, its text ``text``, the strand-level T–N check ``tension_check``), a spectrum's
damage over a sweep (``spectrum``) and a load history reduced to a spectrum
(``load_history``). The physics they use is the library's ``strand.fatigue``."""
