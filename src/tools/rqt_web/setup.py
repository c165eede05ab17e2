from setuptools import find_packages, setup

package_name = 'rqt_web'

setup(
    name=package_name,
    version='0.1.0',
    packages=find_packages(exclude=['test']),
    package_data={package_name: ['static/*']},
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
        ('share/' + package_name, ['package.xml', 'README.md']),
        # `ros2 run rqt_web rqt` looks in lib/<package>/; the launcher there runs bin/rqt.
        ('lib/' + package_name, ['scripts/rqt']),
    ],
    install_requires=['setuptools'],
    zip_safe=False,
    maintainer='Owl Kit Lab',
    maintainer_email='team@owlkitlab.invalid',
    description='rqt in a browser: Node Graph, Message Publisher, Service Caller, Image View.',
    license='Apache-2.0',
    tests_require=['pytest'],
    # `rqt` goes to <prefix>/bin, which the workspace setup puts on PATH.
    entry_points={
        'console_scripts': [
            'rqt = rqt_web.main:main',
        ],
    },
)
