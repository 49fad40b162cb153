"""pool_env.envs: the Gymnasium envs (break, run, 9-ball, 8-ball), their vector envs and the action wrapper."""
