"""The model of a strand: its beams and contact (``model``, ``strand_contact``, ``same_layer``,
``layer_states``, ``contact_settings``), the problem a test set-up loads (``problem``), load
programmes (``programme``), what is read from a solution (``post``, ``pair_results``,
``reactions``, ``fields``), checkpoints, and the distribution over MPI ranks (``partition``,
``parallel``)."""
