from setuptools import find_packages, setup

package_name = 'olive_servo'

setup(
    name=package_name,
    version='0.1.0',
    packages=find_packages(exclude=['test']),
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
        ('share/' + package_name, ['package.xml', 'README.md']),
    ],
    install_requires=['setuptools'],
    zip_safe=True,
    maintainer='Owl Kit Lab',
    maintainer_email='team@owlkitlab.invalid',
    description='Section 4.4 of the Owl Kit course: a sine, the PID test, keys and the IMU steer the servos.',
    license='Apache-2.0',
    tests_require=['pytest'],
    entry_points={
        'console_scripts': [
            'control_servo = olive_servo.control_servo:main',
            'pid_testing = olive_servo.pid_testing:main',
            'keyboard_servos = olive_servo.keyboard_servos:main',
            'imu_control_robot = olive_servo.imu_control_robot:main',
        ],
    },
)
