"""``voot-bench``: the command line (:mod:`.main`) and its subcommands, one module each."""
