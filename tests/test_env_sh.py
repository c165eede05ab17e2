"""What a fresh `source env.sh` leaves in the shell's environment, and what it leaves to the user."""

from env_sh import after_env_sh


def test_openblas_runs_one_thread_unless_the_user_chose_otherwise():
    names = ('OPENBLAS_NUM_THREADS',)
    assert after_env_sh(names, unset=names) == {'OPENBLAS_NUM_THREADS': '1'}
    assert after_env_sh(names, preset={'OPENBLAS_NUM_THREADS': '4'}) == {'OPENBLAS_NUM_THREADS': '4'}
