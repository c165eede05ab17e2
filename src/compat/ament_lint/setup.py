from setuptools import find_packages, setup

package_name = 'ament_lint'

setup(
    name=package_name,
    version='0.17.1',
    packages=find_packages(exclude=['test']),
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
        ('share/' + package_name, ['package.xml', 'README.md']),
    ],
    install_requires=['setuptools'],
    zip_safe=True,
    maintainer='Owl Kit Lab',
    maintainer_email='team@owlkitlab.invalid',
    description="ament's linters' common parts: the linter pytest marker and the ruff runner.",
    license='Apache-2.0',
    tests_require=['pytest'],
    entry_points={
        'pytest11': ['ament_lint = ament_lint.pytest_marker'],
    },
)
