"""What any beam run needs beside its physics, below the cable and the strand model: MPI helpers
(``strand.beam.parallel``), the distribution of a beam mesh and its pair terms over the ranks
(``strand.beam.partition``), the output of a beam's fields (``strand.beam.fields``), typed
records whose fields carry their unit (``strand.beam.records``), settings declared once, with
their unit, sign, choices and meaning (``strand.beam.setting``), and the registry of named
entries every registry of strand is (``strand.beam.registry``)."""
