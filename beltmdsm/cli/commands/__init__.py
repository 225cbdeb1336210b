"""One module per command: ``add(commands, name)`` declares it, ``run(args)`` runs it."""
