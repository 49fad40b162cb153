"""pool_env.records: saved games (`record_game`, `save_game`, `load_game`, `replay`) and videos (`record_video`)."""
