"""The application: a case file → a run → a folder of files.

What ``strand run`` does with the library (``strand`` outside this package): the case and its
settings (``strand.app.case``, ``strand.app.settings``, their checks), the set-up kinds
(``strand.app.kinds``), the run (``strand.app.build``, ``strand.app.runner``,
``strand.app.recording``, ``strand.app.run``), its recorders, summary, figures and fatigue report
(``strand.app.fatigue``), sweeps, comparisons, the folders and the command line
(``strand.app.cli``). The library never imports this package.
"""
