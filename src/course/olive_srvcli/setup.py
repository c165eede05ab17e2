from setuptools import find_packages, setup

package_name = 'olive_srvcli'

setup(
    name=package_name,
    version='0.1.0',
    packages=find_packages(exclude=['test']),
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
        ('share/' + package_name, ['package.xml']),
    ],
    install_requires=['setuptools'],
    zip_safe=True,
    maintainer='Owl Kit Lab',
    maintainer_email='team@owlkitlab.invalid',
    description='Temperature, currency and factorial services with their command-line clients.',
    license='Apache-2.0',
    tests_require=['pytest'],
    entry_points={
        'console_scripts': [
            'temp_server = olive_srvcli.service_temperature:main',
            'temp_client = olive_srvcli.client_temperature:main',
            'currency_server = olive_srvcli.service_currency:main',
            'currency_client = olive_srvcli.client_currency:main',
            'factorial_server = olive_srvcli.service_factorial:main',
            'factorial_client = olive_srvcli.client_factorial:main',
        ],
    },
)
