"""pool_env.play: play a game with the mouse (`python -m pool_env.play`): the session's logic and its drawing."""
